// SPDX-License-Identifier: Apache-2.0
// Viscoelastic maps (issue 24): at each point of a map, after the quasi-static ramp, the contact
// is identified (identification.hpp) at the indentation analysis' bias I_0, and the point gets
// what the paper reports for its three 1D points beside k_fd:
//   omega_n, zeta       the second-order fit of the contact's response (with standard errors)
//   m_eff, b_o          the decomposition with the static tangent stiffness k_o at I_0 (the
//                       indentation's k_tangent at delta0): m_eff = (k_v + k_o) / omega_n^2,
//                       b_o = 2 zeta (k_v + k_o) / omega_n - b_v (analysis/dynamics.hpp)
//   E', E''             the contact's storage and loss moduli E*' = k'/(2a), E*'' = k''/(2a)
//                       (a from delta0 by the Sneddon sphere), averaged over the measured lines:
//                       one number per point for a quantity that depends on frequency (the band
//                       is the map's, the same at every point); the standard error from the
//                       lines' own noise, sigma(Re, Im 1/G) = sigma_G / |G|^2 per line (the
//                       contact radius' uncertainty, common to E' and E'', is not in it)
//
//   palp::MapOptions o;
//   o.dynamic.enabled = true;       // settings: map_dynamic_settings(o.settings) by default
//   palp::StiffnessMap m = palp::map_plan(probe, *robot, rig, plan, "results/pad-dyn", o);
//   palp::MapDynamicGrids g = palp::map_dynamic_grids(m);   // omega_n, zeta, ... per point
//
// Each point's identification is a result directory (identification_result.hpp) beside the
// indentation's: points/r<row>_c<column>_dynamic/; map.json's point gets the keys below and
// "dynamic_dir" (docs/result-format.md "Maps"). reanalyse_dynamic_point() computes the same
// numbers again from the recording, as palpctl analyze map does.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/analysis/indentation.hpp"
#include "palp/identification.hpp"
#include "palp/indent.hpp"
#include "palp/result.hpp"

namespace palp {

struct MapPoint;
struct StiffnessMap;

/// A point's dynamic values (SI, which are also the lab units of their map.json keys); absent
/// where the point has none, with `reason`.
struct DynamicPoint {
  std::optional<double> omega_n_rad_per_s, omega_n_rad_per_s_se, zeta, zeta_se;
  std::optional<double> m_eff_kg, m_eff_kg_se, b_o_N_s_per_m, b_o_N_s_per_m_se;
  std::optional<double> E_storage_Pa, E_storage_Pa_se, E_loss_Pa, E_loss_Pa_se;
  std::string reason;  ///< why some or all are absent (empty when all are present)
};

/// The dynamic part of map options: off by default (a map is quasi-static).
struct MapDynamicOptions {
  bool enabled = false;
  /// The identification at each point; none: map_dynamic_settings(the map's indentation
  /// settings). Its bias must be the indentation analysis' I_0 (map_plan checks, ConfigError).
  std::optional<IdentificationSettings> settings;
};

/// The default identification of a dynamic map: a contact multisine short enough for a grid,
/// with the bias, I_c, K_f and k_v of the indentation's analysis (so k_o and delta0 are at the
/// operating point the response is measured at).
IdentificationSettings map_dynamic_settings(const IndentationSettings& indentation);

/// A point's values from its identification (analysed: run.fit, run.frf) and its indentation's
/// analysis at the same bias (k_o = k_tangent at delta0 with its standard error, delta0; null:
/// no decomposition and no moduli, with the reason), with the instrument's m_v, b_v, k_v from
/// run.settings.instrument and the tip radius from `params`.
DynamicPoint dynamic_point_of(const IdentificationRun& run,
                              const analysis::IndentationResult* indentation,
                              const analysis::IndentationParams& params);

/// The point's identification again from its result directory's recording (identification_
/// run_of + analyze_identification), then dynamic_point_of with `indentation` (re-analysed by
/// the caller as it wants). ConfigError when the result is not an identification.
DynamicPoint reanalyse_dynamic_point(const LoadedResult& identification,
                                     const analysis::IndentationResult* indentation,
                                     const analysis::IndentationParams& params);

/// map.json's dynamic keys of a point (dynamic_dir; omega_n_rad_per_s, omega_n_rad_per_s_se,
/// zeta, ..., E_loss_Pa_se: a number or null with `<key>_reason`; dynamic_reason), written only
/// for a point that has a dynamic result or a reason for none; and back (absent keys: absent
/// values; ConfigError "where: \"zeta\" must be a number or null").
void write_dynamic_point(nlohmann::json& point, const MapPoint& p);
void read_dynamic_point(const nlohmann::json& point, const std::string& where, MapPoint& p);

/// One quantity of the dynamic map: its map.json key, a title with the unit, and the point's
/// value and standard error.
struct DynamicQuantity {
  const char* key;    ///< "omega_n_rad_per_s"
  const char* title;  ///< "ω_n (rad/s)"
  const char* unit;   ///< "rad/s" ("1": none)
  std::optional<double> DynamicPoint::*value;
  std::optional<double> DynamicPoint::*se;
};
/// The six, in the order the files and the report show them.
const std::vector<DynamicQuantity>& dynamic_quantities();

/// The dynamic grids of a map: per quantity (dynamic_quantities' order) the value and the
/// standard error per grid point, row-major, absent where a point has none.
struct MapDynamicGrids {
  int rows = 0, columns = 0;
  std::size_t points_identified = 0;  ///< points with a dynamic result
  std::vector<std::vector<std::optional<double>>> value, se;
};
MapDynamicGrids map_dynamic_grids(const StiffnessMap& map);

}  // namespace palp
