// SPDX-License-Identifier: Apache-2.0
// The known synthetic recording and result of the HDF5 tests: the C++ tests compare them after a
// round trip, and palp-hdf5-fixture writes them for the independent readers (check_h5py.py,
// check_h5dump_layout.py), which assert the same numbers.
#pragma once

#include <filesystem>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "palp/analysis/frf_table.hpp"
#include "palp/hdf5.hpp"
#include "palp/identification_result.hpp"
#include "palp/map.hpp"
#include "palp/recording.hpp"
#include "palp/result.hpp"
#include "test_result_synth.hpp"

namespace palp_test {

/// Five samples at the bottom of a ramp (docs/recording-format.md's example) with every column,
/// a -0.0 in z_mm and a full sidecar. check_h5py.py asserts these numbers.
inline palp::Recording known_recording() {
  palp::Recording r;
  const double t[] = {1.2, 1.201, 1.202, 1.203, 1.204};
  const double i_cmd[] = {0.5, 0.5, 0.51, 0.51, 0.52};
  const double i[] = {0.5012, 0.4987, 0.5093, 0.5104, 0.5211};
  const double z[] = {2.314, -0.0, 2.319, 2.321, 1.2009999999999998};
  const int rep[] = {0, 0, 0, 1, 1};
  for (std::size_t k = 0; k < 5; ++k) {
    palp::RecordingRow row;
    row.sample_index = 1200 + k;
    row.t_s = t[k];
    row.i_cmd_A = i_cmd[k];
    row.i_A = i[k];
    row.z_mm = z[k];
    row.p_Pa = {0.8, 1.1, -0.3, 0.2, 0.5, 1.4 + static_cast<double>(k)};
    row.status = static_cast<std::uint16_t>(33 + 128 * (k == 3));
    row.rep = rep[k];
    r.append(row);
  }
  palp::Sidecar s;
  s.sdk_version = "0.1.0";
  s.created_utc = "2025-03-14T09:26:53Z";
  s.program = {{"kind", "ramp"}, {"repetitions", 2}, {"start_current_A", 0.5}, {"step_current_A", 0.01}};
  s.device = {{"board", "stm32g474"}, {"firmware_version", "1.2.0"}, {"git_hash", "3f9c2e1"},
              {"protocol", "1.0"}, {"serial", "PALP-0042"}};
  s.calibration = {{"current_offset_A", 0.0021}, {"kf_N_per_A", 2.918},
                   {"pressure_offsets_Pa", {12.5, 11.0, 13.25, 12.0, 10.5, 11.75}}};
  s.stroke_origin_z_mm_reason = "the probe was not homed before this run";
  s.zeroing = nlohmann::json::array(
      {{{"committed", false}, {"t_device_s", 0.85}, {"values", {0.0021}}, {"values_unit", "A"},
        {"what", "current_offset"}}});
  s.extra = {{"specimen", "insert, position 3"}};
  r.sidecar = s;
  return r;
}

/// A result as load_result gives it, around known_recording(): check_h5py.py asserts its numbers.
inline palp::LoadedResult known_result() {
  palp::LoadedResult res;
  res.dir = "solid-p3";
  res.experiment = "indentation";
  res.summary = {{"schema", "palp.result/1"},
                 {"experiment", "indentation"},
                 {"created_utc", "2026-11-23T17:21:07Z"},
                 {"sdk_version", "0.1.0"},
                 {"firmware_version", "1.2.0"},
                 {"recordings", {"indentation.csv"}},
                 {"analysis",
                  {{"k_fd_N_per_mm", 0.125},
                   {"delta0_mm", 1.5},
                   {"model_by_aic", "hertz"},
                   {"k_at_depth_N_per_mm", {{"1_mm", 0.25}}},
                   {"E_star_hertz_Pa", nullptr},
                   {"E_star_hertz_Pa_reason", "too few points"}}},
                 {"pressure", {{"contact_point_mm", 25.0}, {"n_loading", 40}, {"channels", nlohmann::json::array()}}}};
  res.recordings.emplace_back("indentation.csv", known_recording());
  return res;
}

/// A half-finished 2 x 2 map in `dir` (written with save_map and write_result): points r1_c1 and
/// r2_c1 indented (synthetic_run(), 2 repetitions) with k_fd 0.5 and 0.25 N/mm in map.json,
/// r1_c2 not indented ("no contact"), r2_c2 not mapped. So its analysis is known: the k_fd grid
/// [[0.5, NaN], [0.25, NaN]] N/mm, row means 0.5 and 0.25, row 2 soft and row 1 stiff, no soft or
/// stiff column, median 0.5 N/mm. check_h5py.py asserts these numbers.
inline palp::LoadedMap known_map(const std::filesystem::path& dir) {
  palp::StiffnessMap m;
  m.plan_name = "pad";
  m.rows = m.columns = 2;
  m.settings = palp::IndentationSettings::preset(palp::IndentationPreset::two_d);
  m.surface.plan_name = "pad";
  m.surface.rows = m.surface.columns = 2;
  m.stopped_because = "cancelled";
  const palp::IndentationRun run = synthetic_run();
  for (const auto& [row, column, k_N_per_mm] : {std::tuple{1, 1, 0.5}, {1, 2, 0.0}, {2, 1, 0.25}}) {
    palp::MapPoint p;
    p.row = row;
    p.column = column;
    p.surface.row = row;
    p.surface.column = column;
    p.surface.ok = true;
    p.surface.x_m = 0.010 * column;
    p.surface.y_m = 0.010 * row;
    if (k_N_per_mm > 0) {
      p.indented = true;
      p.k_fd_N_per_m = k_N_per_mm * 1e3;
      p.result_dir = "points/r" + std::to_string(row) + "_c" + std::to_string(column);
      palp::write_result(dir / p.result_dir, run, palp::Overwrite::yes);
    } else {
      p.reason = "no contact";
    }
    m.points.push_back(p);
    m.surface.points.push_back(p.surface);
  }
  m.resume_index = m.surface.resume_index = m.points.size();
  palp::save_map(dir, m);
  return palp::load_map_results(dir);
}

/// The response of known_identification(): three lines, as analysis::read_frf_table gives
/// frf.csv back. check_h5py.py asserts these numbers.
inline palp::analysis::Frf known_frf() {
  palp::analysis::Frf f;
  const double hz[] = {10.0, 20.0, 40.0}, re[] = {1e-3, 8e-4, 2e-4}, im[] = {-2e-4, -5e-4, -6e-4},
               sigma[] = {1e-6, 2e-6, 3e-6};
  for (std::size_t k = 0; k < 3; ++k) {
    palp::analysis::FrfLine& l = f.lines.emplace_back();
    l.f_Hz = hz[k];
    l.G_m_per_N = {re[k], im[k]};
    l.sigma_m_per_N = sigma[k];
  }
  return palp::analysis::parse_frf_table(palp::format_frf_table(f), "frf.csv");
}

/// A sweep's identification result, as identification_of gives it, around known_recording().
inline palp::LoadedIdentification known_identification() {
  palp::LoadedIdentification id;
  id.result.dir = "sweep";
  id.result.experiment = "identification";
  id.result.summary = {{"schema", "palp.result/1"},
                       {"experiment", "identification"},
                       {"firmware_version", "1.2.0"},
                       {"recordings", {"sweep.csv"}},
                       {"analysis", {{"method", "multisine"}, {"f_n_Hz", 42.5}, {"zeta", 0.3}}}};
  id.result.recordings.emplace_back("sweep.csv", known_recording());
  id.frf = known_frf();
  return id;
}

}  // namespace palp_test
