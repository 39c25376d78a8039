// SPDX-License-Identifier: Apache-2.0
// palpctl map --dynamic and the dynamic part of palpctl analyze map (palp/map_dynamic.hpp):
// the options, the per-point grids in the JSON and the table printed.
#pragma once

#include <optional>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "palp/map.hpp"

namespace palpctl {

struct MapDynamicCli {
  bool enabled = false;
  std::optional<double> amplitude_A;  ///< the multisine's peak; the default settings' otherwise
  std::optional<int> measured_periods;
};

/// --dynamic, --dynamic-amplitude-A, --dynamic-measured-periods.
void add_map_dynamic_options(CLI::App* cmd, MapDynamicCli& o);
/// The SDK options they give, with the map's indentation settings (map_dynamic_settings).
palp::MapDynamicOptions map_dynamic_options(const MapDynamicCli& o,
                                            const palp::IndentationSettings& indentation);

/// The map's dynamic grids in lab units: {"points_identified": n, "<key>": [[row]...],
/// "<key>_se": ...} with null where a point has none; null when no point was identified.
nlohmann::json map_dynamic_json(const palp::StiffnessMap& m);
/// The dynamic grids as tables under the k_fd map; nothing when no point was identified.
void print_map_dynamic(const palp::StiffnessMap& m);

}  // namespace palpctl
