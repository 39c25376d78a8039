// The known synthetic recording and result of the HDF5 tests: the C++ tests compare them after a
// round trip, and palp-hdf5-fixture writes them for the independent readers (check_h5py.py,
// check_h5dump_layout.py), which assert the same numbers.
#pragma once

#include <nlohmann/json.hpp>

#include "palp/recording.hpp"
#include "palp/result.hpp"

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

}  // namespace palp_test
