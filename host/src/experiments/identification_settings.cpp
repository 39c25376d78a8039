// SPDX-License-Identifier: Apache-2.0
// IdentificationSettings (identification.hpp): presets, checks, the device programs they give,
// the excitation's peak and the free-air excursion it predicts.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "experiment_common.hpp"
#include "finite.hpp"
#include "palp/error.hpp"
#include "palp/identification.hpp"

namespace palp {

namespace {

using experiment::kMaxStreamRate_Hz;
constexpr int kMaxMultisineLines = 400;     // the device's synthesiser (multisine_synth.hpp)

void require_identification(bool ok, const std::string& what) {
  if (!ok) throw ConfigError("identification settings: " + what);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Excited harmonics of the multisine: n = 1 (mod line_step) within [f_lo, f_hi] (4k+1 with 4).
long first_harmonic(double f_lo, double f0, int step) {
  long n = static_cast<long>(std::ceil(f_lo / f0 - 1e-6));
  n = std::max(n, 1L);
  while ((n - 1) % step != 0) ++n;
  return n;
}
long last_harmonic(double f_hi, double f0, int step) {
  long n = static_cast<long>(std::floor(f_hi / f0 + 1e-6));
  while (n > 0 && (n - 1) % step != 0) --n;
  return n;
}

}  // namespace

const char* sweep_method_name(SweepMethod m) {
  return m == SweepMethod::stepped ? "stepped" : "multisine";
}

IdentificationSettings IdentificationSettings::preset(IdentificationPreset p) {
  IdentificationSettings s;
  switch (p) {
    case IdentificationPreset::contact_stepped:
      s.method = SweepMethod::stepped;
      break;
    case IdentificationPreset::contact_multisine:
      s.method = SweepMethod::multisine;
      break;
    case IdentificationPreset::contact_multisine_fast:  // identification.hpp: the design
      s.method = SweepMethod::multisine;
      s.amplitude_A = 0.03;
      s.f_lo_Hz = 2.0;
      s.f_hi_Hz = 40.0;
      s.fundamental_Hz = 0.25;
      s.line_step = 2;
      s.discard_periods = 1;
      s.measured_periods = 3;
      s.phase_mode = proto::PhaseMode::schroeder;
      break;
    case IdentificationPreset::free_air:
      s.method = SweepMethod::multisine;
      s.in_contact = false;
      s.bias_A = 0.5;
      s.amplitude_A = 0.01;
      s.f_lo_Hz = 1.0;
      s.f_hi_Hz = 10.0;
      break;
  }
  return s;
}

void IdentificationSettings::validate() const {
  experiment::require_finite(
      "identification settings",
      {{"bias_A", bias_A}, {"amplitude_A", amplitude_A}, {"f_lo_Hz", f_lo_Hz}, {"f_hi_Hz", f_hi_Hz},
       {"step_Hz", step_Hz}, {"settle_min_s", settle_min_s}, {"fundamental_Hz", fundamental_Hz},
       {"stream_rate_Hz", stream_rate_Hz}, {"settle_s", settle_s}, {"contact_current_A", contact_current_A},
       {"max_excursion_m", max_excursion_m}, {"frf.force_constant_N_per_A", frf.force_constant_N_per_A},
       {"frf.stroke_origin_z_m", frf.stroke_origin_z_m}, {"frf.distortion_limit", frf.distortion_limit},
       {"instrument.m_v_kg", instrument.m_v_kg}, {"instrument.b_v_N_s_per_m", instrument.b_v_N_s_per_m},
       {"instrument.k_v_N_per_m", instrument.k_v_N_per_m}, {"fit.adequate_cost", fit.adequate_cost}});
  experiment::require_finite("identification settings", "frf.kf_table_stroke_m", frf.kf_table_stroke_m);
  experiment::require_finite("identification settings", "frf.kf_table_N_per_A", frf.kf_table_N_per_A);
  auto finite = [](double v) { return std::isfinite(v); };
  require_identification(finite(bias_A) && std::fabs(bias_A) <= 4, "bias_A must lie in -4..4 A");
  require_identification(finite(amplitude_A) && amplitude_A > 0 && std::fabs(bias_A) + amplitude_A <= 4,
          "amplitude_A must be positive with |bias_A| + amplitude_A <= 4 A");
  require_identification(finite(f_lo_Hz) && f_lo_Hz >= 0.01, "f_lo_Hz must be at least 0.01 Hz");
  require_identification(finite(f_hi_Hz) && f_hi_Hz > f_lo_Hz && f_hi_Hz <= 125,
          "f_hi_Hz must lie above f_lo_Hz and at most 125 Hz");
  require_identification(finite(stream_rate_Hz) && stream_rate_Hz > 0 && stream_rate_Hz <= kMaxStreamRate_Hz,
          "stream_rate_Hz must lie in (0, 1000] Hz");
  require_identification(stream_rate_Hz >= 8 * f_hi_Hz,
          "stream_rate_Hz " + num(stream_rate_Hz) + " Hz must be at least 8 x f_hi_Hz (" +
              num(8 * f_hi_Hz) + " Hz) to resolve the highest line");
  require_identification(finite(settle_s) && settle_s >= 0 && settle_s <= 60, "settle_s must lie in 0..60 s");
  require_identification(finite(contact_current_A) && contact_current_A > 0 && contact_current_A <= 4,
          "contact_current_A must lie in (0, 4] A");
  require_identification(finite(max_excursion_m) && max_excursion_m > 0, "max_excursion_m must be positive");
  require_identification(finite(frf.force_constant_N_per_A) && frf.force_constant_N_per_A > 0,
          "frf.force_constant_N_per_A must be positive");
  if (method == SweepMethod::stepped) {
    require_identification(finite(step_Hz) && step_Hz >= 0.001 && step_Hz <= f_hi_Hz - f_lo_Hz,
            "step_Hz must lie in 0.001 Hz .. f_hi_Hz - f_lo_Hz");
    require_identification(settle_cycles >= 0 && settle_cycles <= 10000, "settle_cycles must lie in 0..10000");
    require_identification(finite(settle_min_s) && settle_min_s >= 0 && settle_min_s <= 100,
            "settle_min_s must lie in 0..100 s");
    require_identification(measure_cycles >= 1 && measure_cycles <= 10000, "measure_cycles must lie in 1..10000");
    return;
  }
  require_identification(finite(fundamental_Hz) && fundamental_Hz >= 0.001 && fundamental_Hz <= f_lo_Hz,
          "fundamental_Hz must lie in 0.001 Hz .. f_lo_Hz");
  require_identification(line_step >= 1 && line_step <= 1000, "line_step must lie in 1..1000");
  require_identification(discard_periods >= 0 && measured_periods >= 1 &&
              discard_periods + measured_periods <= 65535,
          "discard_periods must be >= 0 and measured_periods >= 1 (at most 65535 in all)");
  require_identification(phase_seed != 0, "phase_seed must not be 0");
  const double per_period = stream_rate_Hz / fundamental_Hz;
  require_identification(std::fabs(per_period - std::round(per_period)) < 1e-6 * per_period,
          "stream_rate_Hz " + num(stream_rate_Hz) + " Hz must give a whole number of samples in "
              "the multisine's period 1/" + num(fundamental_Hz) + " Hz");
  const long first = first_harmonic(f_lo_Hz, fundamental_Hz, line_step);
  const long last = last_harmonic(f_hi_Hz, fundamental_Hz, line_step);
  const long lines = last >= first ? (last - first) / line_step + 1 : 0;
  require_identification(lines >= 3, "the band " + num(f_lo_Hz) + "-" + num(f_hi_Hz) + " Hz holds " +
                          std::to_string(lines) +
                          " excited lines (at least 3 for the fit): widen the band or lower "
                          "fundamental_Hz or line_step");
  require_identification(lines <= kMaxMultisineLines && last <= 65535,
          "the band holds " + std::to_string(lines) + " excited lines, the device plays at most " +
              std::to_string(kMaxMultisineLines) + ": raise line_step or fundamental_Hz");
}

proto::LoadSweep IdentificationSettings::sweep_program() const {
  proto::LoadSweep m;
  m.offset_A = static_cast<float>(bias_A);
  m.amplitude_A = static_cast<float>(amplitude_A);
  m.start_Hz = static_cast<float>(f_lo_Hz);
  m.stop_Hz = static_cast<float>(f_hi_Hz);
  m.step_Hz = static_cast<float>(step_Hz);
  m.settle_cycles = static_cast<std::uint16_t>(settle_cycles);
  m.settle_min_s = static_cast<float>(settle_min_s);
  m.measure_cycles = static_cast<std::uint16_t>(measure_cycles);
  return m;
}

proto::LoadMultisine IdentificationSettings::multisine_program(std::uint32_t control_rate_Hz) const {
  proto::LoadMultisine m;
  m.offset_A = static_cast<float>(bias_A);
  m.fundamental_Hz = static_cast<float>(fundamental_Hz);
  m.line_first = static_cast<std::uint16_t>(first_harmonic(f_lo_Hz, fundamental_Hz, line_step));
  m.line_last = static_cast<std::uint16_t>(last_harmonic(f_hi_Hz, fundamental_Hz, line_step));
  m.line_step = static_cast<std::uint16_t>(line_step);
  m.phase_mode = phase_mode;
  m.phase_seed = phase_seed;
  m.periods = static_cast<std::uint16_t>(discard_periods + measured_periods);
  m.line_amplitude_A = 1.0f;
  const double unit = analysis::multisine_unit_peak(m, control_rate_Hz);
  m.line_amplitude_A = static_cast<float>(amplitude_A / unit);
  return m;
}

double IdentificationSettings::peak_A(std::uint32_t control_rate_Hz) const {
  if (method == SweepMethod::stepped) return static_cast<double>(static_cast<float>(amplitude_A));
  const proto::LoadMultisine m = multisine_program(control_rate_Hz);
  proto::LoadMultisine unit = m;
  unit.line_amplitude_A = 1.0f;
  return static_cast<double>(m.line_amplitude_A) * analysis::multisine_unit_peak(unit, control_rate_Hz);
}

double IdentificationSettings::device_time_s(std::uint32_t control_rate_Hz) const {
  return method == SweepMethod::stepped
             ? analysis::program_duration_s(sweep_program(), control_rate_Hz)
             : analysis::program_duration_s(multisine_program(control_rate_Hz), control_rate_Hz);
}

double IdentificationSettings::predicted_excursion_m() const {
  // |G| of the instrument's second order is unimodal in frequency: its largest value over the
  // band is at the resonance peak clamped into the band.
  const double k = instrument.k_v_N_per_m, m = instrument.m_v_kg, b = instrument.b_v_N_s_per_m;
  const double wn = std::sqrt(k / m), zeta = b / (2 * std::sqrt(k * m));
  const double w_peak = zeta < std::numbers::sqrt2 / 2 ? wn * std::sqrt(1 - 2 * zeta * zeta) : 0.0;
  const double w = std::clamp(w_peak, 2 * std::numbers::pi * f_lo_Hz, 2 * std::numbers::pi * f_hi_Hz);
  const double g = 1 / std::hypot(k - m * w * w, b * w);
  double kf = frf.force_constant_N_per_A;
  for (double v : frf.kf_table_N_per_A) kf = std::max(kf, v);
  return g * kf * amplitude_A;
}

void IdentificationSettings::check_excitation(std::uint32_t control_rate_Hz) const {
  if (in_contact) {
    const double peak = peak_A(control_rate_Hz);
    const double low = bias_A - peak;
    if (!(low > contact_current_A))
      throw ConfigError("identification: bias " + num(bias_A) + " A - peak " + num(peak) +
                        " A = " + num(low) + " A is not above I_c " + num(contact_current_A) +
                        " A: the tip would leave the specimen; raise bias_A or lower "
                        "amplitude_A");
    return;
  }
  const double x = predicted_excursion_m();
  if (x > max_excursion_m)
    throw ConfigError("identification: free air, the predicted peak excursion " + num(x * 1e3) +
                      " mm over " + num(f_lo_Hz) + "-" + num(f_hi_Hz) + " Hz exceeds " +
                      num(max_excursion_m * 1e3) + " mm: lower amplitude_A below " +
                      num(amplitude_A * max_excursion_m / x) + " A");
}

}  // namespace palp
