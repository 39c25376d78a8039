// SPDX-License-Identifier: Apache-2.0
// The coil's I²t thermal model (part of Safety, safety.hpp).
//
// ASSUMPTIONS: the VC250 coil's thermal data is not in the paper; the model and its parameters
// are chosen so that the paper's own protocols (which the coil demonstrably survived) never trip
// it and a sustained 3 A trips it within seconds. Replace them with measured values when known.
//
// Model: E (A²s) is the I²t accumulated above the continuous rating I_c, leaking away with the
// cooling time constant tau, never negative:
//     dE/dt = (i² - I_c²) - E / tau,   E >= 0,   trip when E >= E_lim
// with I_c = Params.i2t_continuous_A, E_lim = Params.i2t_limit_A2s, tau = Params.i2t_tau_s and i
// the measured coil current. E = 0 stands for "no heat above what I_c gives"; a current at or
// below I_c never trips (nor does one up to sqrt(I_c² + E_lim / tau)).
//
// Update: for a current constant over one call, the exact solution
//     E(t + dt) = max(0, tau D + (E(t) - tau D) exp(-dt / tau)),   D = i² - I_c²
// so the model is exact for piecewise-constant current at any step (one tick, or one whole
// staircase step). The tiny per-tick increment (~1e-4 A²s on ~60 A²s at 20 kHz) is added with
// compensated (Kahan) summation, so float keeps the state to a few ulp over hours.
//
// A hold of current i from E = 0 trips after (closed form)
//     t_trip = -tau ln(1 - E_lim / (tau (i² - I_c²)))     (never when tau (i² - I_c²) <= E_lim)
// With the recommended I_c = 2.0 A, E_lim = 60 A²s, tau = 120 s: t_trip(3 A) = 12.643 s.
// (With the catalogue's current I_c = 1.5 A: 9.235 s, but then the paper's 1D protocol trips.)
#pragma once

namespace palp::fw {

/// Fraction of E_lim at which StatusBit::i2t_warning is set.
inline constexpr float kI2tWarningFraction = 0.8f;

class I2tModel {
 public:
  /// I_c (A), E_lim (A²s), tau (s). Keeps the state.
  void configure(float continuous_A, float limit_A2s, float tau_s);
  /// Advances the model by dt_s with coil current i_A (constant over dt_s).
  void update(float i_A, float dt_s);
  void reset();

  /// E, A²s above the continuous rating.
  float excess_A2s() const { return sum_A2s_; }
  /// E / E_lim (Status.i2t_fraction).
  float fraction() const { return limit_A2s_ > 0.0f ? sum_A2s_ / limit_A2s_ : 0.0f; }
  bool over_limit() const { return sum_A2s_ >= limit_A2s_; }
  bool warning() const { return fraction() >= kI2tWarningFraction; }

  float continuous_A() const { return continuous_A_; }
  float limit_A2s() const { return limit_A2s_; }
  float tau_s() const { return tau_s_; }

 private:
  float continuous_A_ = 1.5f;  // the catalogue's Params defaults until configure()
  float limit_A2s_ = 60.0f;
  float tau_s_ = 120.0f;
  float decay_dt_s_ = 0.0f;   // dt the factor below was computed for; 0: not yet
  float one_minus_decay_ = 0.0f;  // 1 - exp(-dt / tau)
  float sum_A2s_ = 0.0f;      // E
  float compensation_A2s_ = 0.0f;  // Kahan: the low-order part lost from sum_A2s_
};

}  // namespace palp::fw
