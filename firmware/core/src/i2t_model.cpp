// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/i2t_model.hpp"

#include <cmath>

namespace palp::fw {

void I2tModel::configure(float continuous_A, float limit_A2s, float tau_s) {
  continuous_A_ = continuous_A;
  limit_A2s_ = limit_A2s;
  tau_s_ = tau_s;
  decay_dt_s_ = 0.0f;
}

void I2tModel::reset() {
  sum_A2s_ = 0.0f;
  compensation_A2s_ = 0.0f;
}

void I2tModel::update(float i_A, float dt_s) {
  if (!(dt_s > 0.0f) || !(tau_s_ > 0.0f)) return;
  if (dt_s != decay_dt_s_) {
    one_minus_decay_ = -std::expm1(-dt_s / tau_s_);
    decay_dt_s_ = dt_s;
  }
  // A non-finite current carries no information: keep the state (Safety trips on it itself).
  if (!std::isfinite(i_A)) return;
  const float steady_A2s = tau_s_ * (i_A * i_A - continuous_A_ * continuous_A_);
  const float step_A2s = (steady_A2s - sum_A2s_) * one_minus_decay_;

  // Kahan summation of sum_A2s_ += step_A2s.
  const float corrected = step_A2s - compensation_A2s_;
  const float next = sum_A2s_ + corrected;
  compensation_A2s_ = (next - sum_A2s_) - corrected;
  sum_A2s_ = next;

  if (sum_A2s_ <= 0.0f) {  // cooled to (or below) the continuous level: the model's floor
    sum_A2s_ = 0.0f;
    compensation_A2s_ = 0.0f;
  }
}

}  // namespace palp::fw
