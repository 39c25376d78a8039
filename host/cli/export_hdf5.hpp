// SPDX-License-Identifier: Apache-2.0
// palpctl export --format hdf5 (issue 22): the HDF5 half of `palpctl export`, called by its
// command (cmd_export.cpp). Built with palp::hdf5 only when HDF5 is found (PALP_HAVE_HDF5);
// without it, hdf5_available() is false and the command says so.
#pragma once

#include <string>

#include "common.hpp"

namespace palpctl {

/// Whether this palpctl was built with palp::hdf5.
bool hdf5_available();

/// Writes INPUT as one HDF5 file (docs/hdf5-format.md): a recording (run.csv with its sidecar,
/// or run.h5), a result directory (result.json), an identification's (sweep, free air: with its
/// frf.csv) or a map directory (map.json and its points; a damaged point is named on stderr, kept
/// in the file as lost, and the others are written). Prints what it wrote (--json: file, format,
/// content, rows, and for a map points, grid_points, complete, results, damaged). ConfigError for
/// an existing --out without --overwrite, or one palp did not write.
int export_hdf5(const Context& ctx, const std::string& input, const std::string& out, bool overwrite);

}  // namespace palpctl
