// SPDX-License-Identifier: Apache-2.0
// A dynamic map's part of a map file (docs/hdf5-format.md "A map file"): the grids of
// map_dynamic_grids and each point's identification group (not installed).
#pragma once

#include <string>

#include "hdf5/h5.hpp"
#include "palp/map.hpp"

namespace palp::hdf5_detail {

/// `/map/dynamic`: per quantity (dynamic_quantities) a rows x columns grid of values and one of
/// standard errors (`<key>_se`), NaN where a point has none, with the unit; the attribute
/// points_identified. Nothing when no point of the map was identified.
void write_map_dynamic_grids(hid_t parent, const Where& w, const StiffnessMap& m);

/// The group of a point's identification under `/map/points`: "r1_c1_dynamic" (its result
/// directory's name).
std::string dynamic_group_name(const MapPoint& p);

}  // namespace palp::hdf5_detail
