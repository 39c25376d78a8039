// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/safety.hpp"

#include <cmath>

namespace palp::fw {

namespace {
using proto::FaultReason;

/// A current in units of 0.1 mA (EventFault.detail), saturated to the int32 range.
std::int32_t tenth_mA(float i_A) {
  const float scaled = i_A * 1e4f;
  if (!(scaled == scaled)) return 0;
  if (scaled >= 2.1e9f) return 2100000000;
  if (scaled <= -2.1e9f) return -2100000000;
  return static_cast<std::int32_t>(std::lround(scaled));
}
}  // namespace

Safety::Safety(const proto::Params& params) { configure(params); }

void Safety::configure(const proto::Params& params) {
  params_ = params;
  i2t_.configure(params.i2t_continuous_A, params.i2t_limit_A2s, params.i2t_tau_s);
}

bool Safety::overcurrent_now(float i_measured_A) const {
  return std::fabs(i_measured_A) > params_.current_clamp_A + kOvercurrentMargin_A;
}

bool Safety::travel_out(std::int32_t encoder_counts) const {
  return encoder_counts < params_.travel_min_counts || encoder_counts > params_.travel_max_counts;
}

std::uint64_t Safety::watchdog_elapsed_us(std::uint64_t now_wd_us) const {
  return now_wd_us > last_feed_us_ ? now_wd_us - last_feed_us_ : 0;  // a clock reset is fresh
}

void Safety::latch(FaultReason reason, std::int32_t detail) {
  if (tripped() || reason == FaultReason::none) return;
  fault_ = reason;
  fault_detail_ = detail;
}

void Safety::trip(FaultReason reason, std::int32_t detail) { latch(reason, detail); }

void Safety::feed(std::uint64_t now_wd_us) { last_feed_us_ = now_wd_us; }

SafetyVerdict Safety::check(const SafetyInputs& in) {
  const bool was_tripped = tripped();
  last_measured_A_ = in.i_measured_A;
  last_encoder_counts_ = in.encoder_counts;

  // The thermal model runs on the measured current, faulted or not (it must keep cooling).
  i2t_.update(in.i_measured_A, in.dt_s);

  if (!std::isfinite(in.i_request_A)) latch(FaultReason::internal, 1);
  if (!std::isfinite(in.i_measured_A)) latch(FaultReason::internal, 2);
  latch(in.sensor.reason, in.sensor.detail);  // none latches nothing

  if (overcurrent_now(in.i_measured_A)) {
    if (in.dt_s > 0.0f) overcurrent_s_ += in.dt_s;
    // half a tick of tolerance: float sums of dt land just below a whole number of ticks
    if (overcurrent_s_ + 0.5f * in.dt_s >= kOvercurrentTime_s)
      latch(FaultReason::overcurrent, tenth_mA(in.i_measured_A));
  } else {
    overcurrent_s_ = 0.0f;
  }

  if (travel_out(in.encoder_counts)) latch(FaultReason::travel_limit, in.encoder_counts);

  if (i2t_.over_limit()) latch(FaultReason::i2t, tenth_mA(in.i_measured_A));

  heartbeat_armed_ = in.i_request_A != 0.0f || in.program_running;
  const std::uint64_t timeout_us = std::uint64_t{params_.heartbeat_timeout_ms} * 1000u;
  const std::uint64_t elapsed_us = watchdog_elapsed_us(in.watchdog_now_us);
  if (heartbeat_armed_ && elapsed_us > timeout_us) {
    const std::uint64_t late_ms = (elapsed_us - timeout_us) / 1000u;
    latch(FaultReason::heartbeat_timeout,
          late_ms > 2000000000u ? 2000000000 : static_cast<std::int32_t>(late_ms));
  }

  SafetyVerdict verdict;
  verdict.tripped = tripped();
  verdict.new_fault = (!was_tripped && verdict.tripped) ? fault_ : FaultReason::none;
  if (verdict.tripped) {
    verdict.i_set_A = 0.0f;
    return verdict;
  }
  const float clamp_A = params_.current_clamp_A;
  verdict.i_set_A = in.i_request_A;
  if (in.i_request_A > clamp_A) {
    verdict.i_set_A = clamp_A;
    verdict.clamped = true;
  } else if (in.i_request_A < -clamp_A) {
    verdict.i_set_A = -clamp_A;
    verdict.clamped = true;
  }
  return verdict;
}

ClearResult Safety::clear(std::uint64_t now_wd_us, bool sensor_cause_present) {
  if (!tripped()) return ClearResult::not_latched;
  bool persists = false;
  switch (fault_) {
    case FaultReason::overcurrent:
      persists = overcurrent_now(last_measured_A_) || !std::isfinite(last_measured_A_);
      break;
    case FaultReason::travel_limit:
      persists = travel_out(last_encoder_counts_);
      break;
    case FaultReason::i2t:
      persists = i2t_.fraction() > kI2tReleaseFraction;
      break;
    case FaultReason::heartbeat_timeout:
      persists = watchdog_elapsed_us(now_wd_us) >
                 std::uint64_t{params_.heartbeat_timeout_ms} * 1000u;
      break;
    case FaultReason::internal:
      persists = !std::isfinite(last_measured_A_);
      break;
    case FaultReason::driver_fault:
    case FaultReason::supply_undervoltage:
    case FaultReason::current_sense_error:
    case FaultReason::encoder_error:
      persists = sensor_cause_present;
      break;
    default:
      break;
  }
  if (persists) return ClearResult::cause_persists;
  fault_ = FaultReason::none;
  fault_detail_ = 0;
  overcurrent_s_ = 0.0f;
  return ClearResult::cleared;
}

}  // namespace palp::fw
