// SPDX-License-Identifier: Apache-2.0
// The atomic result directory shared by every experiment's writer (result.hpp describes the
// guarantee): files are written into a hidden sibling directory, flushed, and the directory is
// renamed into place. Every result directory holds kManifestFile, the list of the files palp
// wrote into it; Overwrite::yes replaces only a directory whose every entry that list names
// (check_replaceable, result.hpp), moves it aside, and deletes only those files.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "palp/recording.hpp"
#include "palp/result.hpp"

namespace palp {

/// The manifest in every result directory: one file name a line, the files palp wrote there.
inline constexpr const char* kManifestFile = ".palp-files";

/// Writes text to a new file and flushes it; RecordingError naming the file on failure.
void write_text_file(const std::filesystem::path& p, const std::string& text);

/// The checks before an experiment's writer builds anything: `dir` made absolute and normal,
/// naming a directory (else ConfigError "<who>: DIR names no directory"), its parent created,
/// and an existing `dir` refused without Overwrite::yes, and with it unless check_replaceable
/// passes. Returns the absolute path.
std::filesystem::path prepare_result_directory(const std::filesystem::path& dir, Overwrite overwrite,
                                               const char* who);

/// The head every result.json starts with: schema, experiment, created_utc, sdk_version, in that
/// order; the writers add the other top-level keys in docs/result-format.md's order after it.
nlohmann::ordered_json result_head(const char* experiment);

/// Creates the hidden sibling of `dir` (absolute, normalised), lets `fill` write the files into
/// it, adds the manifest of what fill wrote, flushes and renames it to `dir` (an existing `dir`
/// is checked again, moved aside, and only its manifest's files are deleted). On any error the sibling is removed and the error
/// propagates (filesystem errors as RecordingError naming `dir`). The caller has checked
/// whether `dir` exists when overwrite is Overwrite::no.
void write_result_directory(const std::filesystem::path& dir, Overwrite overwrite,
                            const std::function<void(const std::filesystem::path& tmp)>& fill);

/// A single file palp writes whole (a tidy CSV, a report page): how an existing one is known to
/// be palp's, and what a refusal says after the file's path.
struct OwnFileKind {
  std::string_view head;    ///< the bytes every such file palp writes begins with
  std::string not_regular;  ///< "is not a report palp wrote (not a regular file)"
  std::string not_ours;     ///< "was not written by palp (its first line does not begin ...)"
};

/// Whether `file` may be written: absent, or (with Overwrite::yes) a regular file beginning with
/// kind.head. Else ConfigError "<file> already exists; ..." or "<file> <kind's words>: nothing
/// was replaced; move it away, or choose another file".
void check_own_file_replaceable(const std::filesystem::path& file, Overwrite overwrite,
                                const OwnFileKind& kind);

/// Writes `make_text()`'s text as `file` atomically: `file` checked (check_own_file_replaceable)
/// before the text is made and again before the rename, its directory created, a hidden temporary
/// sibling written and flushed, renamed into place, the directory synced. ConfigError for a file
/// that may not be written (or a path naming no file), RecordingError when the disk refuses.
void write_own_file(const std::filesystem::path& file, Overwrite overwrite, const OwnFileKind& kind,
                    const std::function<std::string()>& make_text);

}  // namespace palp
