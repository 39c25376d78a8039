// SPDX-License-Identifier: Apache-2.0
// IndentationSettings (indent.hpp): presets, the device program, checks.
#include <cmath>
#include <string>

#include "experiment_common.hpp"
#include "finite.hpp"
#include "palp/error.hpp"
#include "palp/indent.hpp"

namespace palp {

namespace {

using experiment::kCountM;
using experiment::kMaxStreamRate_Hz;

// levels of a staircase from `from` toward `to` by `step`, `to` included when on the grid (the
// firmware's grid_points)
double levels(double from, double to, double step) {
  return std::floor(std::fabs(to - from) / step + 1e-3) + 1;
}

void require_indentation(bool ok, const std::string& what) {
  if (!ok) throw ConfigError("indentation settings: " + what);
}

}  // namespace

const char* preset_name(IndentationPreset p) { return p == IndentationPreset::one_d ? "1d" : "2d"; }

IndentationSettings IndentationSettings::preset(IndentationPreset p) {
  IndentationSettings s;
  if (p == IndentationPreset::two_d) {
    s.dwell_s = 0.025;
    s.repetitions = 3;
  }
  return s;
}

RampProgram IndentationSettings::ramp_program() const {
  RampProgram m;
  m.start_A = static_cast<float>(start_A);
  m.stop_A = static_cast<float>(stop_A);
  m.step_A = static_cast<float>(step_A);
  m.dwell_s = static_cast<float>(dwell_s);
  m.repetitions = static_cast<std::uint16_t>(repetitions);
  m.unload = unload ? 1 : 0;
  m.displacement_limit_counts = static_cast<std::uint32_t>(std::lround(displacement_limit_m / kCountM));
  return m;
}

double IndentationSettings::ramp_duration_s() const {
  const double n = levels(start_A, stop_A, step_A);
  return (unload ? 2 * n - 1 : n) * dwell_s * repetitions;
}

void IndentationSettings::validate() const {
  const auto& a = analysis;
  experiment::require_finite(
      "indentation settings",
      {{"start_A", start_A}, {"stop_A", stop_A}, {"step_A", step_A}, {"dwell_s", dwell_s},
       {"displacement_limit_m", displacement_limit_m}, {"stream_rate_Hz", stream_rate_Hz},
       {"zero_pressure_s", zero_pressure_s}, {"settle_s", settle_s},
       {"analysis.force_constant_N_per_A", a.force_constant_N_per_A},
       {"analysis.contact_current_A", a.contact_current_A}, {"analysis.spring_N_per_m", a.spring_N_per_m},
       {"analysis.tip_radius_m", a.tip_radius_m}, {"analysis.poisson", a.poisson},
       {"analysis.bias_current_A", a.bias_current_A},
       {"analysis.thickness.thickness_m", a.thickness ? a.thickness->thickness_m : 0.0},
       {"analysis.window_lo_m", a.window_lo_m}, {"analysis.window_hi_m", a.window_hi_m},
       {"analysis.local_half_width_m", a.local_half_width_m},
       {"analysis.force_noise_N", a.force_noise_N.value_or(0.0)},
       {"analysis.stroke_origin_z_m", a.stroke_origin_z_m}});
  experiment::require_finite("indentation settings", "analysis.tangent_depths_m", a.tangent_depths_m);
  experiment::require_finite("indentation settings", "analysis.kf_table_stroke_m", a.kf_table_stroke_m);
  experiment::require_finite("indentation settings", "analysis.kf_table_N_per_A", a.kf_table_N_per_A);
  auto finite = [](double v) { return std::isfinite(v); };
  require_indentation(finite(start_A) && std::fabs(start_A) <= 4, "start_A must lie in -4..4 A");
  require_indentation(finite(stop_A) && std::fabs(stop_A) <= 4, "stop_A must lie in -4..4 A");
  require_indentation(stop_A > start_A, "stop_A must be above start_A (the ramp pushes into the specimen)");
  require_indentation(finite(step_A) && step_A >= 1e-4 && step_A <= stop_A - start_A,
          "step_A must lie in 0.0001 A .. stop_A - start_A");
  require_indentation(finite(dwell_s) && dwell_s >= 1e-4 && dwell_s <= 100, "dwell_s must lie in 0.0001..100 s");
  require_indentation(repetitions >= 1 && repetitions <= 1000, "repetitions must lie in 1..1000");
  require_indentation(finite(displacement_limit_m) && displacement_limit_m >= 0 && displacement_limit_m <= 0.1,
          "displacement_limit_m must lie in 0..0.1 m (0: no limit)");
  require_indentation(finite(stream_rate_Hz) && stream_rate_Hz > 0 && stream_rate_Hz <= kMaxStreamRate_Hz,
          "stream_rate_Hz must lie in (0, 1000] Hz");
  require_indentation(finite(zero_pressure_s) && zero_pressure_s >= 0.01 && zero_pressure_s <= 60,
          "zero_pressure_s must lie in 0.01..60 s");
  require_indentation(finite(settle_s) && settle_s >= 0 && settle_s <= 60, "settle_s must lie in 0..60 s");
}

}  // namespace palp
