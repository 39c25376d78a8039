// SPDX-License-Identifier: Apache-2.0
// The coil current loop: a PI controller from current set-point (A) to coil voltage (V).
//
// Design: pole-zero cancellation. The coil is an RL load, i' = (v - R i) / L. A PI controller
// C(s) = Kp + Ki / s with
//     Kp = L * wc,   Ki = R * wc                       (continuous-time design)
// puts its zero on the coil's pole R/L, so the open loop is wc / s and the closed loop is the
// first-order lag wc / (s + wc): bandwidth wc, no overshoot, 1 % settling in ln(100) / wc.
//
// The tick (20 or 40 kHz, Params.control_rate_Hz) is not fast against wc, so the loop uses the
// exact zero-order-hold equivalent of that design for the actual tick period dt: with
//     a = exp(-R dt / L)     (the coil's pole over one tick)
//     g = 1 - exp(-wc dt)    (the wanted closed-loop step per tick)
//     Kp = a R g / (1 - a),  Ki = R g / dt
// and the integrator I += Ki dt e (backward Euler, v = Kp e + I), the controller's zero sits
// exactly on the sampled coil pole and the sampled closed loop is i(k) = 1 - exp(-wc k dt) for a
// unit step, at any dt. As dt -> 0 these gains tend to L wc and R wc (checked by a test).
// At 1.5 kHz: 20 kHz -> Kp = 14.49 V/A, Ki = 43 590 V/(A s); 40 kHz -> 16.78 V/A, 48 701 V/(A s).
// Step: 1 % settling at ln(100) / wc = 489 us (the 10th tick at 20 kHz, the 20th at 40 kHz).
//
// Saturation and anti-windup: the output is limited to +-supply_V (Params.supply_V, 24 V by
// default). The integrator is clamped (conditional integration): while the unsaturated output
// is beyond the limit and the error pushes further out, it does not integrate; it is also kept
// within +-supply_V. A 0 -> 3 A step (43 V asked, 24 V available) therefore ends without
// overshoot, where a plain PI overshoots by about 12 %.
//
// Delay: the model above applies the voltage computed at tick k during tick k (as palp-sim
// does). A board whose PWM takes the new duty one tick later sees a second-order loop with
// poles |z| = sqrt(g): at 20 kHz about 8.5 % overshoot, still settled within 1 ms (tested).
//
// Per-tick code is float only; the gains are recomputed (two expf) only when dt changes.
#pragma once

namespace palp::fw {

/// Coil electrical constants (paper §II-A, DESIGN.md table).
inline constexpr float kCoilResistance_Ohm = 5.8f;
inline constexpr float kCoilInductance_H = 2.07e-3f;
/// Closed-loop bandwidth of the current loop (first-order, -3 dB).
inline constexpr float kCurrentLoopBandwidth_Hz = 1500.0f;
/// Supply voltage when Params.supply_V has not been applied.
inline constexpr float kDefaultSupply_V = 24.0f;

struct CurrentLoopConfig {
  float resistance_Ohm = kCoilResistance_Ohm;
  float inductance_H = kCoilInductance_H;
  float bandwidth_Hz = kCurrentLoopBandwidth_Hz;
  float supply_V = kDefaultSupply_V;
};

struct CurrentLoopGains {
  float kp_V_per_A = 0.0f;
  float ki_V_per_A_s = 0.0f;
};

/// The exact discrete pole-zero-cancelling gains for one tick period (see the top of the file).
CurrentLoopGains current_loop_gains(const CurrentLoopConfig& config, float dt_s);

class CurrentLoop {
 public:
  explicit CurrentLoop(const CurrentLoopConfig& config = {});

  /// One control tick: the coil voltage to apply until the next tick, within +-supply_V.
  /// dt_s is the actual tick period; a non-positive or non-finite dt_s gives 0 V and holds the
  /// integrator.
  float update(float setpoint_A, float measured_A, float dt_s);

  /// Clears the integrator and the saturation flag (e.g. after a fault or at program start).
  void reset();

  /// Params.supply_V: the output limit. Takes effect at the next update().
  void set_supply_V(float supply_V);
  void configure(const CurrentLoopConfig& config);

  /// The last update()'s output was at the supply limit (StatusBit::voltage_saturated).
  bool saturated() const { return saturated_; }
  float voltage_V() const { return voltage_V_; }
  float integrator_V() const { return integrator_V_; }
  /// The gains in force for the last dt_s passed to update().
  const CurrentLoopGains& gains() const { return gains_; }
  const CurrentLoopConfig& config() const { return config_; }

 private:
  CurrentLoopConfig config_;
  CurrentLoopGains gains_{};
  float gains_dt_s_ = 0.0f;  // dt the gains were computed for; 0: not yet
  float integrator_V_ = 0.0f;
  float voltage_V_ = 0.0f;
  bool saturated_ = false;
};

}  // namespace palp::fw
