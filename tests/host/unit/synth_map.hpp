// SPDX-License-Identifier: Apache-2.0
// A synthetic map directory with known stiffnesses, written by the SDK's own writers
// (write_result per point, save_map for map.json): for the tidy CSV's tests (SDK and palpctl).
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include "palp/map.hpp"
#include "palp/result.hpp"
#include "test_analysis_synth.hpp"

namespace palp::test {

/// The known linear stiffness of the specimen at a point of the synthetic map, N/m:
/// 1.5, 2.0 (row 1), 2.5, 3.0 N/mm (row 2); 2.5 at row 1, column 3.
inline double synth_k_N_per_m(int row, int column) { return 1e3 * (0.5 + 1.0 * row + 0.5 * (column - 1)); }

/// An indentation run as indent() returns it, of a linear specimen of stiffness k: the staircase
/// 0.5 -> 1.5 A by 5 mA and back, `reps` times, contact at contact_z_m, with 0.2 mA rms of
/// current noise (so the repetitions differ; seeded, so every run is the same).
inline IndentationRun synth_linear_run(double k_N_per_m, double contact_z_m, int reps) {
  analysis::test::SynthSpec spec;
  spec.object_force = [k_N_per_m](double d) { return d > 0 ? k_N_per_m * d : 0.0; };
  spec.contact_z_m = contact_z_m;
  spec.i_top_A = 1.5;
  spec.i_step_A = 0.005;
  spec.reps = reps;
  spec.command_column = true;
  spec.noise_A = 2e-4;
  const analysis::Curve c = analysis::test::synth_curve(spec);
  IndentationRun run;
  run.settings = IndentationSettings::preset(IndentationPreset::two_d);
  run.settings.stop_A = 1.5;
  run.settings.step_A = 0.005;
  run.settings.repetitions = reps;
  run.device.serial = "SYNTH-0001";
  run.device.board = "synthetic";
  run.device.firmware_version = "1.0.0";
  run.program.repetitions_done = reps;
  for (Eigen::Index k = 0; k < c.z_m.size(); ++k) {
    RecordingRow row;
    row.sample_index = static_cast<std::uint64_t>(k);
    row.t_s = 0.025 * static_cast<double>(k);
    row.i_cmd_A = c.i_cmd_A[k];
    row.i_A = c.i_A[k];
    row.z_mm = c.z_m[k] * 1e3;
    row.rep = c.rep[k] - 1;
    run.recording.append(row);
  }
  Sidecar side;
  side.device = device_json(run.device);
  side.program = {{"kind", "ramp"}};
  run.recording.sidecar = side;
  analyze_run(run);
  return run;
}

/// A rows x columns map in `dir` (complete; every touch at x = 10 mm per column, y = 20 mm per
/// row, the arm pointing straight down the work object's z), each point a result directory of
/// synth_linear_run with k_N_per_m(row, column) (synth_k_N_per_m unless given), written by
/// write_result and save_map.
inline StiffnessMap write_synth_map(const std::filesystem::path& dir, int rows, int columns, int reps,
                                    const std::function<double(int, int)>& k_N_per_m = synth_k_N_per_m) {
  StiffnessMap m;
  m.plan_name = "synthetic";
  m.rows = rows;
  m.columns = columns;
  m.settings = IndentationSettings::preset(IndentationPreset::two_d);
  m.surface.plan_name = m.plan_name;
  m.surface.rows = rows;
  m.surface.columns = columns;
  for (int r = 1; r <= rows; ++r)
    for (int c = 1; c <= columns; ++c) {
      MapPoint p;
      p.row = r;
      p.column = c;
      p.surface.row = r;
      p.surface.column = c;
      p.surface.ok = true;
      p.surface.tcp_at_rest = Pose{0.010 * c, 0.020 * r, 0.1, 0, 0, 0};
      p.surface.stroke_at_rest_m = 2e-3;
      p.result_dir = "points/r" + std::to_string(r) + "_c" + std::to_string(c);
      const IndentationRun run = synth_linear_run(k_N_per_m(r, c), 12e-3, reps);
      write_result(dir / p.result_dir, run);
      p.indented = true;
      p.k_fd_N_per_m = run.analysis->k_fd_N_per_m.value;
      m.points.push_back(p);
      m.surface.points.push_back(p.surface);
    }
  m.resume_index = m.surface.resume_index = m.points.size();
  m.complete = m.surface.complete = true;
  save_map(dir, m);
  return load_map(dir);
}

}  // namespace palp::test
