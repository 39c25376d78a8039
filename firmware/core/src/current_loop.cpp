// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/current_loop.hpp"

#include <cmath>

namespace palp::fw {

namespace {
constexpr float kTwoPi = 6.28318530717958647692f;

float clamp_abs(float value, float limit) {
  if (value > limit) return limit;
  if (value < -limit) return -limit;
  return value;
}
}  // namespace

CurrentLoopGains current_loop_gains(const CurrentLoopConfig& config, float dt_s) {
  const float r = config.resistance_Ohm;
  const float wc = kTwoPi * config.bandwidth_Hz;
  // 1 - a and g via expm1, which keeps full precision when the exponent is small (fast ticks).
  const float one_minus_a = -std::expm1(-r * dt_s / config.inductance_H);
  const float a = 1.0f - one_minus_a;
  const float g = -std::expm1(-wc * dt_s);
  CurrentLoopGains gains;
  gains.kp_V_per_A = a * r * g / one_minus_a;
  gains.ki_V_per_A_s = r * g / dt_s;
  return gains;
}

CurrentLoop::CurrentLoop(const CurrentLoopConfig& config) : config_(config) {}

void CurrentLoop::configure(const CurrentLoopConfig& config) {
  config_ = config;
  gains_dt_s_ = 0.0f;  // recompute at the next update
}

void CurrentLoop::set_supply_V(float supply_V) { config_.supply_V = supply_V; }

void CurrentLoop::reset() {
  integrator_V_ = 0.0f;
  voltage_V_ = 0.0f;
  saturated_ = false;
}

float CurrentLoop::update(float setpoint_A, float measured_A, float dt_s) {
  if (!(dt_s > 0.0f) || !std::isfinite(dt_s)) {
    voltage_V_ = 0.0f;
    saturated_ = false;
    return voltage_V_;
  }
  if (dt_s != gains_dt_s_) {
    gains_ = current_loop_gains(config_, dt_s);
    gains_dt_s_ = dt_s;
  }
  const float limit_V = config_.supply_V;
  const float error_A = setpoint_A - measured_A;
  const float proportional_V = gains_.kp_V_per_A * error_A;
  const float integrated_V = integrator_V_ + gains_.ki_V_per_A_s * dt_s * error_A;
  const float unsaturated_V = proportional_V + integrated_V;

  // Conditional integration: hold the integrator while the output is beyond the limit and the
  // error would drive it further out.
  const bool pushing_up = unsaturated_V > limit_V && error_A > 0.0f;
  const bool pushing_down = unsaturated_V < -limit_V && error_A < 0.0f;
  if (!pushing_up && !pushing_down) integrator_V_ = clamp_abs(integrated_V, limit_V);

  const float wanted_V = proportional_V + integrator_V_;
  voltage_V_ = clamp_abs(wanted_V, limit_V);
  saturated_ = voltage_V_ != wanted_V;
  if (!std::isfinite(voltage_V_)) {  // a NaN measurement: never drive the coil with it
    integrator_V_ = 0.0f;
    voltage_V_ = 0.0f;
    saturated_ = false;
  }
  return voltage_V_;
}

}  // namespace palp::fw
