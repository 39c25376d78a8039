// SPDX-License-Identifier: Apache-2.0
// A recording as a group of an HDF5 file (docs/hdf5-format.md "A recording's group"): shared by
// the recording file and the result file (not installed).
#pragma once

#include <filesystem>

#include "hdf5/h5.hpp"
#include "palp/recording.hpp"

namespace palp::hdf5_detail {

/// Creates the group `w.object` under `parent` with the recording's columns and attributes.
/// ConfigError (nothing written) for unequal columns, no samples, a value that is not finite or
/// a sidecar that cannot be written.
void write_recording_group(hid_t parent, const Where& w, const Recording& recording);

/// Reads the group `name` under `parent` (at `w_parent`) back; `file` bounds the rows a column
/// may claim. RecordingError naming the object for anything write_recording_group would not have
/// written.
Recording read_recording_group(hid_t parent, const char* name, const Where& w_parent,
                               const std::filesystem::path& file);

}  // namespace palp::hdf5_detail
