// SPDX-License-Identifier: Apache-2.0
// Safety: current clamp, coil I²t model, travel limits, overcurrent, host heartbeat watchdog and
// the fault latch (DESIGN.md "Firmware principles"). Any fault drives the current to zero at
// once: the only set-point the current loop may use is the one check() returns, and it is 0 A
// from the very call that trips until clear() is accepted.
//
// Use, every control tick:
//     const SafetyVerdict verdict = safety.check({i_request_A, i_measured_A, encoder_counts,
//                                                program_running, dt_s, watchdog_now_us,
//                                                sensor_monitor.update(readings)});
//     const float v = current_loop.update(verdict.i_set_A, i_measured_A, dt_s);
// (with the set-point 0 A the loop pulls the current down at up to -supply_V: from 3 A to 0
// in about 0.2 ms). On every valid host request: safety.feed(watchdog_now_us).
//
// Checks (first match wins when several trip in the same call; the first latched fault stays):
//   internal           the requested or measured current is not a finite number;
//   sensor faults      what the SensorMonitor (sensor_monitor.hpp) found this tick:
//                      driver_fault, supply_undervoltage, current_sense_error, encoder_error,
//                      with its detail;
//   overcurrent        |measured i| > current_clamp_A + kOvercurrentMargin_A (0.25 A) for
//                      kOvercurrentTime_s (1 ms) in a row, control time; detail: i in 0.1 mA;
//   travel_limit       encoder outside [travel_min_counts, travel_max_counts]; detail: count;
//   i2t                the I²t model (i2t_model.hpp) of the measured current reaches its limit;
//                      detail: measured i in 0.1 mA;
//   heartbeat_timeout  armed and watchdog_now - last feed > heartbeat_timeout_ms; detail: ms
//                      late. Armed while the requested current is not 0 or a program runs.
// trip() latches the reasons the core cannot see itself (host_request, control_overrun,
// internal).
//
// Current clamp: |i_request| > current_clamp_A is limited to +-current_clamp_A and reported
// (SafetyVerdict::clamped, StatusBit::current_clamped). It is not a fault.
//
// Two clocks: dt_s is the control clock (virtual time in palp-sim); the heartbeat watchdog
// counts only on watchdog_now_us, its own clock (the MCU timer on hardware, wall time in
// palp-sim), so simulation speed never trips it (DESIGN.md "Conventions").
//
// clear() releases the latch only when the cause is gone, judged on the latest check() inputs:
//   overcurrent: |measured i| <= clamp + margin;  travel_limit: encoder back within the limits;
//   i2t: the model cooled to <= kI2tReleaseFraction (50 %) of its limit (after a trip at 3 A,
//   about 7 s at 0 A with the recommended parameters);
//   heartbeat_timeout: fed within the timeout (the FaultClear request itself feeds);
//   the sensor faults: the SensorMonitor no longer sees the cause (clear()'s sensor_cause_present);
//   the reasons passed to trip(): nothing the core can judge; their reporter trips again if the
//   condition is still there.
#pragma once

#include <cstdint>

#include "palp/fw/i2t_model.hpp"
#include "palp/fw/sensor_monitor.hpp"
#include "palp/protocol/messages.hpp"

namespace palp::fw {

inline constexpr float kOvercurrentMargin_A = 0.25f;
inline constexpr float kOvercurrentTime_s = 1e-3f;
/// clear() of an i2t fault is accepted once the model is at or below this fraction of its limit.
inline constexpr float kI2tReleaseFraction = 0.5f;

/// One control tick's inputs to Safety::check().
struct SafetyInputs {
  float i_request_A = 0.0f;          // set-point asked for (program or host), before the clamp
  float i_measured_A = 0.0f;         // measured coil current, calibrated
  std::int32_t encoder_counts = 0;   // extended encoder position
  bool program_running = false;
  float dt_s = 0.0f;                 // control tick period (control clock)
  std::uint64_t watchdog_now_us = 0; // the watchdog's own clock
  SensorFinding sensor{};            // a sensor or power-stage fault found this tick
};

/// What the tick may do.
struct [[nodiscard]] SafetyVerdict {
  float i_set_A = 0.0f;     // the only set-point the current loop may use: clamped; 0 if tripped
  bool tripped = false;     // the fault latch is set (this call or earlier): current to zero
  bool clamped = false;     // the request was limited to current_clamp_A
  proto::FaultReason new_fault = proto::FaultReason::none;  // set in the call that tripped
};

enum class ClearResult : std::uint8_t {
  cleared,        // the latch was set and is now released
  not_latched,    // nothing to clear
  cause_persists, // refused (Nak fault_persists): the cause is still present
};

class Safety {
 public:
  explicit Safety(const proto::Params& params = {});
  /// Applies Params (limits, I²t parameters, heartbeat timeout). Keeps the latch and the I²t
  /// state.
  void configure(const proto::Params& params);

  /// The per-tick check; see the top of the file.
  SafetyVerdict check(const SafetyInputs& in);
  /// A valid host request arrived at watchdog time now_wd_us.
  void feed(std::uint64_t now_wd_us);
  /// Latches a fault the core cannot detect itself (first fault wins).
  void trip(proto::FaultReason reason, std::int32_t detail);
  /// Releases the latch if the cause is gone (see the top of the file). sensor_cause_present:
  /// the SensorMonitor still sees the cause of a sensor fault (SensorMonitor::cause_present).
  ClearResult clear(std::uint64_t now_wd_us, bool sensor_cause_present = false);

  bool tripped() const { return fault_ != proto::FaultReason::none; }
  proto::FaultReason fault() const { return fault_; }
  /// EventFault.detail of the latched fault.
  std::int32_t fault_detail() const { return fault_detail_; }

  bool heartbeat_armed() const { return heartbeat_armed_; }
  float i2t_fraction() const { return i2t_.fraction(); }
  bool i2t_warning() const { return i2t_.warning(); }
  const I2tModel& i2t() const { return i2t_; }

 private:
  bool overcurrent_now(float i_measured_A) const;
  bool travel_out(std::int32_t encoder_counts) const;
  std::uint64_t watchdog_elapsed_us(std::uint64_t now_wd_us) const;
  void latch(proto::FaultReason reason, std::int32_t detail);

  proto::Params params_;
  I2tModel i2t_;
  proto::FaultReason fault_ = proto::FaultReason::none;
  std::int32_t fault_detail_ = 0;
  std::uint64_t last_feed_us_ = 0;
  float overcurrent_s_ = 0.0f;  // control time the measured current has been beyond the margin
  float last_measured_A_ = 0.0f;
  std::int32_t last_encoder_counts_ = 0;
  bool heartbeat_armed_ = false;
};

}  // namespace palp::fw
