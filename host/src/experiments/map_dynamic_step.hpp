// SPDX-License-Identifier: Apache-2.0
// The step a dynamic map runs at each point after the ramp (map_dynamic.hpp), for map.cpp.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "palp/identification.hpp"
#include "palp/indent.hpp"
#include "palp/map.hpp"

namespace palp::detail {

/// ConfigError, before anything moves, for settings a dynamic map cannot use: invalid ones, free
/// air, or a bias other than the indentation analysis' I_0.
void check_dynamic_settings(const IdentificationSettings& s,
                            const IndentationSettings& indentation);

/// The point's identification result directory beside its indentation's ("points/r1_c1_dynamic").
std::string dynamic_dir_of(const std::string& result_dir);

/// Identifies the contact where the probe is (identify(): the coil floats to the surface and
/// holds the bias), writes map_dir/dynamic_dir_of(p.result_dir) and fills p.dynamic_dir and
/// p.dynamic from it and the indentation's analysis. False when cancelled (nothing written).
bool identify_map_point(Probe& probe, const IdentificationSettings& s,
                        const IndentationRun& indentation, const std::filesystem::path& map_dir,
                        MapPoint& p, const std::function<bool()>& cancelled);

}  // namespace palp::detail
