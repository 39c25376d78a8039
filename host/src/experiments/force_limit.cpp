// SPDX-License-Identifier: Apache-2.0
// Ramps that stop at an object force (force_limit.hpp).
#include "palp/force_limit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "palp/error.hpp"

namespace palp {

namespace {

std::string limit_num(double v, const char* fmt = "%.4g") {
  char b[32];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

// the staircase's currents in order, one per dwell (the firmware's RampProgram: the top level
// held once, the start level at both ends of a repetition)
std::vector<double> force_limit_levels_A(const IndentationSettings& s) {
  const auto n = static_cast<int>(std::floor((s.stop_A - s.start_A) / s.step_A + 1e-3));
  std::vector<double> out;
  for (int k = 0; k <= n; ++k) out.push_back(s.start_A + s.step_A * k);
  if (s.unload)
    for (int k = n - 1; k >= 0; --k) out.push_back(s.start_A + s.step_A * k);
  return out;
}

}  // namespace

CoilLimits CoilLimits::of(const Params& p) {
  return CoilLimits{p.current_clamp_A, p.i2t_continuous_A, p.i2t_limit_A2s, p.i2t_tau_s};
}

double top_current_for_force_A(const analysis::IndentationParams& a, double force_N,
                               double depth_m) {
  return a.contact_current_A + (force_N + a.spring_N_per_m * depth_m) / a.force_constant_N_per_A;
}

double ramp_i2t_peak_A2s(const IndentationSettings& s, const CoilLimits& lim) {
  const double tau = lim.i2t_tau_s, cont2 = lim.i2t_continuous_A * lim.i2t_continuous_A;
  // the model's exact solution over a constant current: E -> tau (i^2 - I_cont^2) with time
  // constant tau, floored at 0 (monotone within a level: its peak is at a level's end)
  double e = 0, peak = 0;
  auto hold = [&](double i_A, double t_s) {
    const double steady = tau * (i_A * i_A - cont2);
    e = std::max(0.0, steady + (e - steady) * std::exp(-t_s / tau));
    peak = std::max(peak, e);
  };
  const std::vector<double> levels = force_limit_levels_A(s);
  for (int point = 0; point < 10000; ++point) {  // to the periodic state of a map's points
    const double at_start = e;
    for (int r = 0; r < s.repetitions; ++r)
      for (double i : levels) hold(i, s.dwell_s);
    hold(s.start_A, s.settle_s);
    if (point > 0 && std::abs(e - at_start) < 1e-9) break;
  }
  return peak;
}

void check_max_force(const IndentationSettings& s, double max_force_N, const CoilLimits& lim) {
  auto n = [](double v, const char* fmt = "%.4g") { return limit_num(v, fmt); };
  if (!std::isfinite(max_force_N) || max_force_N <= 0)
    throw ConfigError("max_force_N must be a positive force, not " + n(max_force_N) + " N");
  if (!(s.displacement_limit_m > 0))
    throw ConfigError("max_force_N needs the ramp's displacement limit (displacement_limit_m is "
                      "0): it bounds the depth, and so the top current, a force needs");
  const auto& a = s.analysis;
  const double kf = a.force_constant_N_per_A, ic = a.contact_current_A, kv = a.spring_N_per_m;
  const double depth = s.displacement_limit_m;
  const double top = top_current_for_force_A(a, max_force_N, depth);
  const std::string asked = "max_force_N " + n(max_force_N) + " N";
  const std::string how = "(I_c " + n(ic) + " A + (" + n(max_force_N) + " N + k_v " + n(kv) +
                          " N/m x " + n(depth * 1e3) + " mm displacement limit) / K_f " + n(kf) +
                          " N/A)";
  if (top > lim.current_clamp_A) {
    const double most = std::floor(100 * (kf * (lim.current_clamp_A - ic) - kv * depth)) / 100;
    throw ConfigError(asked + " needs up to " + n(top, "%.3f") + " A at the ramp's top " + how +
                      ", above the coil's current clamp " + n(lim.current_clamp_A) +
                      " A: at most " + n(most, "%.2f") + " N");
  }
  const double peak = ramp_i2t_peak_A2s(settings_for_max_force(s, max_force_N, depth), lim);
  if (peak > kI2tWarningFraction * lim.i2t_limit_A2s)
    throw ConfigError(asked + ": the ramp to " + n(top, "%.3f") + " A " + how + ", " +
                      std::to_string(s.repetitions) + " repetitions of " + n(s.dwell_s * 1e3) +
                      " ms steps, heats the coil's I2t model to " + n(peak, "%.1f") +
                      " A^2 s, above " + n(100 * kI2tWarningFraction) + " % of its " +
                      n(lim.i2t_limit_A2s) + " A^2 s trip level (continuous " +
                      n(lim.i2t_continuous_A) + " A, tau " + n(lim.i2t_tau_s) +
                      " s): ask for less force, fewer repetitions or shorter steps");
}

IndentationSettings settings_for_max_force(IndentationSettings s, double max_force_N,
                                           double expected_depth_m) {
  const double depth = std::clamp(expected_depth_m, 0.0, s.displacement_limit_m);
  const double top = top_current_for_force_A(s.analysis, max_force_N, depth);
  const double span = top - s.start_A;
  if (span > 0) {
    const double levels = std::max(1.0, std::ceil(span / s.step_A - 1e-9));
    s.step_A = span / levels;
  }
  s.stop_A = top;
  return s;
}

std::optional<RampTop> ramp_top_of(const IndentationRun& run) {
  const analysis::Curve c = curve_of(run.recording);
  const auto& a = run.settings.analysis;
  const auto n = c.z_m.size();
  if (n == 0) return std::nullopt;
  const bool commanded = c.i_cmd_A.size() == n;
  auto level = [&](Eigen::Index k) { return commanded ? c.i_cmd_A[k] : c.i_A[k]; };
  double top = -1e9;
  Eigen::Index end = 0;  // the first repetition's loading branch: up to its highest level
  for (Eigen::Index k = 0; k < n; ++k) {
    if (c.rep.size() == n && c.rep[k] != c.rep[0]) break;
    if (level(k) > top + 1e-7) top = level(k);
    if (level(k) < top - 1e-7) break;
    end = k + 1;
  }
  RampTop t;
  int m = 0;
  for (Eigen::Index k = 0; k < end; ++k) {
    if (std::abs(level(k) - top) > 1e-7) continue;
    const double depth = c.z_m[k] - run.float_z_m;
    t.force_N +=
        a.force_constant_N_per_A * (c.i_A[k] - a.contact_current_A) - a.spring_N_per_m * depth;
    t.depth_m += depth;
    ++m;
  }
  if (m == 0) return std::nullopt;
  t.force_N /= m;
  t.depth_m /= m;
  return t;
}

}  // namespace palp
