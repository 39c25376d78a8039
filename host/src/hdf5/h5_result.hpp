// SPDX-License-Identifier: Apache-2.0
// A result directory as an HDF5 group (docs/hdf5-format.md "A result's group"): shared by the
// result file, each point of a map file and the identification file (not installed).
#pragma once

#include <filesystem>

#include "hdf5/h5.hpp"
#include "palp/result.hpp"

namespace palp::hdf5_detail {

/// Creates the group `w.object` under `parent`: result.json as text and its numbers as typed
/// attributes, every recording as a group, and for an indentation its repetitions (each one's
/// rows of the recording and, when the result re-analyses, its numbers). ConfigError (from the
/// recording writer) for a result that cannot be written.
void write_result_group(hid_t parent, const Where& w, const LoadedResult& result);

/// Reads the group `name` under `parent` (at `w_parent`) back: `summary` and `recordings` as
/// load_result gives them, `dir` set to `file`. RecordingError naming the object for anything
/// write_result_group would not have written.
LoadedResult read_result_group(hid_t parent, const char* name, const Where& w_parent,
                               const std::filesystem::path& file);

}  // namespace palp::hdf5_detail
