// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/encoder.hpp"

#include <cmath>

namespace palp::fw {

namespace {
constexpr float kTwoPi = 6.28318530717958647692f;

/// The signed difference of two wrapping 16-bit counts (two's complement, no UB).
std::int32_t wrapped_difference(std::uint16_t now, std::uint16_t before) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(now - before));
}

/// a + b with 32-bit wrap-around instead of signed overflow.
std::int32_t add_wrapping(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}
}  // namespace

Encoder::Encoder(float velocity_cutoff_Hz) : cutoff_Hz_(velocity_cutoff_Hz) {}

void Encoder::reset(std::uint16_t timer_count, std::int32_t position_counts) {
  last_timer_count_ = timer_count;
  position_counts_ = position_counts;
  last_step_counts_ = 0;
  velocity_counts_per_s_ = 0.0f;
  index_latched_ = false;
}

void Encoder::update(std::uint16_t timer_count, float dt_s) {
  const std::int32_t step = wrapped_difference(timer_count, last_timer_count_);
  last_timer_count_ = timer_count;
  last_step_counts_ = step;
  position_counts_ = add_wrapping(position_counts_, step);
  if (!(dt_s > 0.0f)) return;  // position stays exact; no velocity without a period
  if (dt_s != alpha_dt_s_) {
    alpha_ = -std::expm1(-kTwoPi * cutoff_Hz_ * dt_s);
    alpha_dt_s_ = dt_s;
  }
  const float raw_counts_per_s = static_cast<float>(step) / dt_s;
  velocity_counts_per_s_ += alpha_ * (raw_counts_per_s - velocity_counts_per_s_);
}

void Encoder::latch_index() {
  index_position_counts_ = position_counts_;
  index_latched_ = true;
}

void Encoder::latch_index_at(std::uint16_t timer_count_at_index) {
  // The captured count is near the last one read: extend it relative to that.
  index_position_counts_ =
      add_wrapping(position_counts_, wrapped_difference(timer_count_at_index, last_timer_count_));
  index_latched_ = true;
}

}  // namespace palp::fw
