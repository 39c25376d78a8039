// The atomic result directory shared by every experiment's writer (result.hpp describes the
// guarantee): files are written into a hidden sibling directory, flushed, and the directory is
// renamed into place; Overwrite::yes moves an existing one aside first and deletes it after.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "palp/recording.hpp"

namespace palp {

/// Writes text to a new file and flushes it; RecordingError naming the file on failure.
void write_text_file(const std::filesystem::path& p, const std::string& text);

/// The checks before an experiment's writer builds anything: `dir` made absolute and normal,
/// naming a directory (else ConfigError "<who>: DIR names no directory"), its parent created,
/// and an existing `dir` refused without Overwrite::yes. Returns the absolute path.
std::filesystem::path prepare_result_directory(const std::filesystem::path& dir, Overwrite overwrite,
                                               const char* who);

/// The head every result.json starts with: schema, experiment, created_utc, sdk_version.
nlohmann::json result_head(const char* experiment);

/// Creates the hidden sibling of `dir` (absolute, normalised), lets `fill` write the files into
/// it, flushes and renames it to `dir`. On any error the sibling is removed and the error
/// propagates (filesystem errors as RecordingError naming `dir`). The caller has checked
/// whether `dir` exists when overwrite is Overwrite::no.
void write_result_directory(const std::filesystem::path& dir, Overwrite overwrite,
                            const std::function<void(const std::filesystem::path& tmp)>& fill);

}  // namespace palp
