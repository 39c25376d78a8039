// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/sensor_monitor.hpp"

#include <cmath>

namespace palp::fw {

namespace {
using proto::FaultReason;

// value * scale rounded, saturated to the int32 range (0 for NaN): an EventFault.detail
std::int32_t detail_of(float value, float scale) {
  const float scaled = value * scale;
  if (!(scaled == scaled)) return 0;
  if (scaled >= 2.1e9f) return 2100000000;
  if (scaled <= -2.1e9f) return -2100000000;
  return static_cast<std::int32_t>(std::lround(scaled));
}

// half a tick of tolerance: float sums of dt land just below a whole number of ticks
bool lasted(float accumulated_s, float dt_s, float limit_s) {
  return accumulated_s + 0.5f * dt_s >= limit_s;
}
}  // namespace

void SensorMonitor::configure(float supply_nominal_V, std::int32_t stroke_origin_counts) {
  supply_nominal_V_ = supply_nominal_V;
  stroke_origin_counts_ = stroke_origin_counts;
}

bool SensorMonitor::coil_must_move(const SensorReadings& in) const {
  if (!(std::fabs(in.i_measured_A - still_ref_A_) >= kEncoderStillDelta_A)) return false;
  const std::int32_t stroke = in.encoder_counts - stroke_origin_counts_;
  if (stroke < kStopZoneCounts) return in.i_measured_A >= kRearStopLiftOff_A;
  if (stroke > kStrokeCounts - kStopZoneCounts) return in.i_measured_A <= kFrontStopRelease_A;
  return true;
}

SensorFinding SensorMonitor::update(const SensorReadings& in) {
  const float dt = in.dt_s > 0.0f ? in.dt_s : 0.0f;

  driver_fault_ = in.driver_fault;

  supply_V_ = in.supply_V;
  const bool supply_low = !(in.supply_V >= kSupplyMinFraction * supply_nominal_V_);
  supply_low_s_ = supply_low ? supply_low_s_ + dt : 0.0f;

  // the current-sense reading: at the rail, or frozen while the voltage moved
  sense_at_rail_ = std::fabs(in.i_sense_A) >= kCurrentSenseRail_A;
  if (started_ && in.i_sense_A == last_sense_A_) {
    sense_same_s_ += dt;
    if (in.v_applied_V < sense_v_min_V_) sense_v_min_V_ = in.v_applied_V;
    if (in.v_applied_V > sense_v_max_V_) sense_v_max_V_ = in.v_applied_V;
  } else {
    sense_same_s_ = 0.0f;
    sense_v_min_V_ = sense_v_max_V_ = in.v_applied_V;
  }
  last_sense_A_ = in.i_sense_A;
  sense_stuck_ = lasted(sense_same_s_, dt, kSenseStuckTime_s) &&
                 sense_v_max_V_ - sense_v_min_V_ >= kSenseStuckSpan_V;

  // the encoder: a jump beyond the coil's reach, or no count while the coil had to move
  const float limit_counts = kMaxCoilSpeed_m_per_s * 1e6f * dt;  // 1 count = 1 um
  const std::int32_t step = in.encoder_step_counts;
  encoder_jumped_ = std::fabs(static_cast<float>(step)) > limit_counts;
  if (!started_ || step != 0) {
    still_ref_A_ = in.i_measured_A;
    must_move_s_ = 0.0f;
  } else {
    must_move_s_ = coil_must_move(in) ? must_move_s_ + dt : 0.0f;
  }
  encoder_stuck_ = lasted(must_move_s_, dt, kEncoderStillTime_s);
  started_ = true;

  SensorFinding f;
  if (driver_fault_) {
    f = {FaultReason::driver_fault, detail_of(in.i_measured_A, 1e4f)};
  } else if (lasted(supply_low_s_, dt, kSupplyLowTime_s)) {
    f = {FaultReason::supply_undervoltage, detail_of(in.supply_V, 1e3f)};
  } else if (sense_at_rail_ || sense_stuck_) {
    f = {FaultReason::current_sense_error, detail_of(in.i_sense_A, 1e4f)};
  } else if (encoder_jumped_) {
    f = {FaultReason::encoder_error, step};
  } else if (encoder_stuck_) {
    f = {FaultReason::encoder_error, 0};
  }
  return f;
}

bool SensorMonitor::cause_present(proto::FaultReason reason) const {
  switch (reason) {
    case FaultReason::driver_fault:
      return driver_fault_;
    case FaultReason::supply_undervoltage:
      return !(supply_V_ >= kSupplyMinFraction * supply_nominal_V_);
    case FaultReason::current_sense_error:
      return sense_at_rail_ || sense_stuck_;
    case FaultReason::encoder_error:
      return encoder_stuck_;
    default:
      return false;
  }
}

}  // namespace palp::fw
