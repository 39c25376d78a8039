// SPDX-License-Identifier: Apache-2.0
// palpctl map --dynamic: options, JSON grids and printed tables (map_dynamic_cli.hpp).
#include "map_dynamic_cli.hpp"

#include <cstdio>
#include <string>

namespace palpctl {

using nlohmann::json;

void add_map_dynamic_options(CLI::App* cmd, MapDynamicCli& o) {
  cmd->add_flag(
      "--dynamic", o.enabled,
      "After each point's ramp, identify the contact at the analysis' bias (a 16 s multisine "
      "per point, contact_multisine_fast) and map omega_n, zeta, m_eff, b_o, E' and E'' beside "
      "k_fd; each point's "
      "identification in OUT_DIR/points/r<row>_c<column>_dynamic/");
  cmd->add_option("--dynamic-amplitude-A", o.amplitude_A,
                  "--dynamic: the multisine's true peak about the bias, A (default 0.03)")
      ->check(CLI::Range(0.001, 0.45));
  cmd->add_option("--dynamic-measured-periods", o.measured_periods,
                  "--dynamic: multisine periods averaged (>= 2 for a noise estimate; default 3)")
      ->check(CLI::Range(1, 100));
}

palp::MapDynamicOptions map_dynamic_options(const MapDynamicCli& o,
                                            const palp::IndentationSettings& indentation) {
  palp::MapDynamicOptions d;
  d.enabled = o.enabled;
  if (!o.enabled) {
    if (o.amplitude_A || o.measured_periods)
      throw palp::ConfigError(
          "--dynamic-amplitude-A and --dynamic-measured-periods need --dynamic");
    return d;
  }
  palp::IdentificationSettings s = palp::map_dynamic_settings(indentation);
  if (o.amplitude_A) s.amplitude_A = *o.amplitude_A;
  if (o.measured_periods) s.measured_periods = *o.measured_periods;
  d.settings = s;
  return d;
}

json map_dynamic_json(const palp::StiffnessMap& m) {
  const palp::MapDynamicGrids g = palp::map_dynamic_grids(m);
  if (g.points_identified == 0) return nullptr;
  json j = {{"points_identified", g.points_identified}};
  const auto grid = [&](const std::vector<std::optional<double>>& v) {
    json rows = json::array();
    for (int r = 0; r < g.rows; ++r) {
      json row = json::array();
      for (int c = 0; c < g.columns; ++c) {
        const auto& x = v[static_cast<std::size_t>(r * g.columns + c)];
        row.push_back(x ? json(*x) : json(nullptr));
      }
      rows.push_back(std::move(row));
    }
    return rows;
  };
  for (std::size_t q = 0; q < palp::dynamic_quantities().size(); ++q) {
    const std::string key = palp::dynamic_quantities()[q].key;
    j[key] = grid(g.value[q]);
    j[key + "_se"] = grid(g.se[q]);
  }
  return j;
}

void print_map_dynamic(const palp::StiffnessMap& m) {
  const palp::MapDynamicGrids g = palp::map_dynamic_grids(m);
  if (g.points_identified == 0) return;
  for (std::size_t q = 0; q < palp::dynamic_quantities().size(); ++q) {
    std::printf("%s:\n      ", palp::dynamic_quantities()[q].title);
    for (int c = 1; c <= g.columns; ++c) std::printf(" col %-5d", c);
    std::printf("\n");
    for (int r = 1; r <= g.rows; ++r) {
      std::printf("row %-2d", r);
      for (int c = 1; c <= g.columns; ++c) {
        const auto& v = g.value[q][static_cast<std::size_t>((r - 1) * g.columns + c - 1)];
        if (v)
          std::printf(" %9.4g", *v);
        else
          std::printf(" %9s", "-");
      }
      std::printf("\n");
    }
  }
}

}  // namespace palpctl
