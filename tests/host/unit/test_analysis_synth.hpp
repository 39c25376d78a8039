// SPDX-License-Identifier: Apache-2.0
// Synthetic quasi-static indentation recordings with a known answer (for the analysis tests).
#pragma once

#include <cmath>
#include <functional>
#include <random>

#include "palp/analysis/indentation.hpp"

namespace palp::analysis::test {

struct SynthSpec {
  std::function<double(double)> object_force;  ///< F_o(delta), 0 for delta <= 0
  double contact_z_m = 12.3456789e-3;
  double i_start_A = 0.5, i_top_A = 1.5, i_step_A = 0.001;
  int reps = 5;
  int samples_per_level = 1;  ///< samples recorded at each current level (the dwell)
  double noise_A = 0.0;        ///< rms current noise
  double quantum_m = 0.0;      ///< encoder resolution (1e-6), 0 = none
  unsigned seed = 20261122;
  IndentationParams params{};
  bool command_column = false;  ///< fill Curve::i_cmd_A with each level's current
  /// > 0: the probe does not jump to each level's rest position but follows it as a damped
  /// oscillator of this natural frequency and damping ratio (palp-sim's coil in contact rings
  /// at ~10 Hz with zeta ~0.25), integrated over samples dt_s apart
  double natural_Hz = 0.0, damping = 0.25, dt_s = 1e-3;
};

/// Loading then symmetric unloading per repetition. The probe sits where the coil force
/// K_f (i - I_c) balances k_v delta + F_o(delta) (in air: k_v delta alone).
inline Curve synth_curve(const SynthSpec& s) {
  const auto& p = s.params;
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int steps = static_cast<int>(std::lround((s.i_top_A - s.i_start_A) / s.i_step_A));
  const int levels = 2 * steps + 1;
  const int per_rep = levels * s.samples_per_level;
  Curve c;
  c.z_m.resize(per_rep * s.reps);
  c.i_A.resize(per_rep * s.reps);
  c.rep.resize(per_rep * s.reps);
  if (s.command_column) c.i_cmd_A.resize(per_rep * s.reps);
  const double w = 2.0 * 3.14159265358979323846 * s.natural_Hz;
  for (int r = 0; r < s.reps; ++r) {
    double x = NAN, v = 0.0;  // the oscillator's position and velocity
    for (int k = 0; k < per_rep; ++k) {
      const int lv = k / s.samples_per_level;
      const int level = lv <= steps ? lv : 2 * steps - lv;
      const double i = s.i_start_A + level * s.i_step_A;
      const double F = p.force_constant_N_per_A * (i - p.contact_current_A);
      double delta;
      if (F <= 0.0) {
        delta = F / p.spring_N_per_m;
      } else {
        double lo = 0.0, hi = 0.05;
        for (int it = 0; it < 56; ++it) {
          const double mid = 0.5 * (lo + hi);
          (p.spring_N_per_m * mid + s.object_force(mid) < F ? lo : hi) = mid;
        }
        delta = 0.5 * (lo + hi);
      }
      double z = s.contact_z_m + delta;
      if (s.natural_Hz > 0.0) {  // semi-implicit Euler towards the level's rest position
        if (std::isnan(x)) x = z;
        v += s.dt_s * (w * w * (z - x) - 2.0 * s.damping * w * v);
        x += s.dt_s * v;
        z = x;
      }
      if (s.quantum_m > 0.0) z = std::round(z / s.quantum_m) * s.quantum_m;
      const int n = r * per_rep + k;
      c.z_m[n] = z;
      c.i_A[n] = i + s.noise_A * noise(rng);
      c.rep[n] = r + 1;
      if (s.command_column) c.i_cmd_A[n] = i;
    }
  }
  return c;
}

}  // namespace palp::analysis::test
