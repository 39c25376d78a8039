// SPDX-License-Identifier: Apache-2.0
// Known synthetic results for the report's figure tests (report-plots): an indentation of a
// Hertz specimen with known E* and pressure channels of known slope (test_result_synth.hpp's
// run, written as a result directory), an identification of a second-order system with known
// omega_n and zeta, and a traced surface with known heights and tilts.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "palp/result.hpp"
#include "palp/trace.hpp"

namespace palp_test::report {

/// The indentation: palp_test::synthetic_run() (E* = 125.8 kPa, z_c = 25 mm, 2 repetitions,
/// channel m reading 20 m Pa per newton of F_o), written to dir.
std::filesystem::path write_known_indentation(const std::filesystem::path& dir);

/// The identification's truth: G = 1 / (m s^2 + b s + k).
inline constexpr double kM_kg = 0.16, kK_N_per_m = 400.0, kZeta = 0.2;
double known_omega_n();  ///< sqrt(k / m) = 50 rad/s
double known_b();        ///< 2 zeta sqrt(k m)
/// Lines from 0.5 to 40 Hz (f_n = 7.96 Hz), noise-free G with sigma = 2 % of |G| at 8 Hz,
/// analysed (fit_second_order), with free_air and viscoelastic blocks, written to dir with
/// write_identification_result.
std::filesystem::path write_known_identification(const std::filesystem::path& dir);

/// A complete 4 x 5 trace: z = 10 + 0.5 (column - 1) mm (a plane tilted about the y axis by
/// atan(0.5 / 10) = 2.862 deg, columns 10 mm apart), every normal tilted by that angle; the
/// point (row 2, column 3) failed ("no contact within 15.000 mm of travel").
palp::TracedSurface known_trace();
inline constexpr double kTraceTiltDeg = 2.8624052261117479;

/// A 9 x 9 heat map (vega::heat_map) of k = 0.3 + 0.01 row N/mm in columns 2, 5, 8 and
/// 0.6 + 0.01 row elsewhere, each cell linking to "#r<row>c<column>", columns 2, 5, 8 outlined
/// "soft" and row 9 "stiff": the paper's Fig. 6(b) as the map's report draws it.
nlohmann::json known_outlined_heat_map();

/// A figure spec's embedded data set `name` (its "values"); std::out_of_range when absent.
inline const nlohmann::json& data_values(const nlohmann::json& spec, const std::string& name) {
  for (const auto& d : spec.at("data"))
    if (d.at("name") == name) return d.at("values");
  throw std::out_of_range("no data set \"" + name + "\" in the spec");
}
/// The linear interpolation of a data set's y_field at x (rows in increasing x).
double interpolate(const nlohmann::json& rows, const std::string& x_field,
                   const std::string& y_field, double x);
/// Paper-like examples to look at (not checked by the tests): a 3-repetition staircase of 25
/// samples per level at 1 kHz on a Hertz specimen with current noise and the coil ringing at
/// 10 Hz (Fig. 6(a)'s protocol), channels 1 and 6 with a loading/unloading gap (Fig. 5(c)), and
/// a second-order response with measurement noise (Fig. 4(d)).
std::filesystem::path write_paper_like_indentation(const std::filesystem::path& dir);
std::filesystem::path write_paper_like_identification(const std::filesystem::path& dir);

/// A fresh temporary directory for one test (emptied; removed when the program ends).
std::filesystem::path fresh_dir(const std::string& name);

}  // namespace palp_test::report
