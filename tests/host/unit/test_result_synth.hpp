// SPDX-License-Identifier: Apache-2.0
// A synthetic indentation run with a known answer, as indent() returns it: the result directory
// tests (test_result.cpp) and the HDF5 result tests (tests/host/hdf5) write and read it.
#pragma once

#include <cmath>

#include "palp/result.hpp"
#include "test_analysis_synth.hpp"

namespace palp_test {

inline constexpr double kEstar = 125.8e3;  // Pa, the 1D phantoms' bulk modulus
inline constexpr double kR = 2.5e-3;

/// A run as indent() returns it, from a synthetic Hertz staircase (2 repetitions, known E*).
inline palp::IndentationRun synthetic_run() {
  palp::analysis::test::SynthSpec spec;
  spec.object_force = [](double d) {
    return d > 0 ? 4.0 / 3.0 * kEstar * std::sqrt(kR) * std::pow(d, 1.5) : 0.0;
  };
  spec.contact_z_m = 25e-3;
  spec.i_top_A = 1.5;
  spec.i_step_A = 0.01;
  spec.reps = 2;
  spec.quantum_m = 1e-6;
  const palp::analysis::Curve c = palp::analysis::test::synth_curve(spec);
  palp::IndentationRun run;
  run.settings = palp::IndentationSettings::preset(palp::IndentationPreset::one_d);
  run.settings.stop_A = 1.5;
  run.settings.repetitions = 2;
  run.device.serial = "SIM-0001";
  run.device.board = "palp-sim";
  run.device.firmware_version = "1.2.3";
  run.program.repetitions_done = 2;
  for (Eigen::Index k = 0; k < c.z_m.size(); ++k) {
    palp::RecordingRow row;
    row.sample_index = static_cast<std::uint64_t>(k);
    row.t_s = 0.1 * static_cast<double>(k);
    row.i_cmd_A = c.i_A[k];
    row.i_A = c.i_A[k];
    row.z_mm = std::round(c.z_m[k] * 1e6) / 1e3;
    row.rep = c.rep[k] - 1;
    // channel m reads 20 m Pa per newton of object force (a pressure-force test of known slope)
    const double Fo = spec.object_force(c.z_m[k] - spec.contact_z_m);
    for (std::size_t m = 0; m < 6; ++m) row.p_Pa[m] = 20.0 * static_cast<double>(m + 1) * Fo;
    run.recording.append(row);
  }
  palp::Sidecar side;
  side.device = palp::device_json(run.device);
  side.program = {{"kind", "ramp"}};
  run.recording.sidecar = side;
  palp::analyze_run(run);
  return run;
}

}  // namespace palp_test
