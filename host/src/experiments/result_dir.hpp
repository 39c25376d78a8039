// The atomic result directory shared by every experiment's writer (result.hpp describes the
// guarantee): files are written into a hidden sibling directory, flushed, and the directory is
// renamed into place; Overwrite::yes moves an existing one aside first and deletes it after.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "palp/recording.hpp"

namespace palp {

/// "2025-01-31T14:05:09Z", now.
std::string utc_now();

/// Writes text to a new file and flushes it; RecordingError naming the file on failure.
void write_text_file(const std::filesystem::path& p, const std::string& text);

/// Creates the hidden sibling of `dir` (absolute, normalised), lets `fill` write the files into
/// it, flushes and renames it to `dir`. On any error the sibling is removed and the error
/// propagates (filesystem errors as RecordingError naming `dir`). The caller has checked
/// whether `dir` exists when overwrite is Overwrite::no.
void write_result_directory(const std::filesystem::path& dir, Overwrite overwrite,
                            const std::function<void(const std::filesystem::path& tmp)>& fill);

}  // namespace palp
