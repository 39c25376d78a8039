// SPDX-License-Identifier: Apache-2.0
// Sensor and actuator plausibility: the checks that tell a failed sensor or power stage from the
// physics it should be measuring (docs/reliability.md section 5). Every control tick the
// controller hands it the raw readings; what it finds goes to Safety (SafetyInputs::sensor_fault),
// which latches it like any other fault: 0 V in the same tick, EventFault, fault_latched in every
// later sample.
//
// Checks, in this order (the first one present is reported), all on control time:
//   driver_fault         the H-bridge driver's fault line is asserted (the driver filters it
//                        itself): at the first tick it is seen. detail: measured current, 0.1 mA.
//   supply_undervoltage  the measured bridge supply is below kSupplyMinFraction (75 %) of
//                        Params.supply_V (18 V of 24 V) for kSupplyLowTime_s (1 ms) in a row, or
//                        not a number. detail: the supply in mV at the trip.
//   current_sense_error  (a) the raw current-sense reading is at the end of the current-sense
//                        ADC's range (|i| >= kCurrentSenseRail_A, the last code of +-5 A): at
//                        the first such tick, since the loop would act on a reading that is
//                        no measurement at all; (b) the raw reading has been bit-identical for
//                        kSenseStuckTime_s (1 ms) while the coil voltage applied meanwhile
//                        spanned kSenseStuckSpan_V (2 V) or more: a 2 V step moves the coil's
//                        current (L/R = 0.36 ms) by about 0.3 A in 1 ms, over a hundred ADC codes.
//                        detail: the raw reading, 0.1 mA.
//   encoder_error        (a) a jump: the encoder moved more than kMaxCoilSpeed_m_per_s (5 m/s,
//                        250 counts at 20 kHz, 125 at 40 kHz) in one tick; the clamp's force
//                        over the whole 34 mm stroke reaches about 3 m/s. detail: the counts of
//                        the jump (signed, |detail| > the limit). (b) stuck: the count has not
//                        changed while, for kEncoderStillTime_s (10 ms) in a row, the measured
//                        current has been kEncoderStillDelta_A (0.5 A) or more away from the
//                        current when the count last changed (1.5 N or more of coil force: a
//                        soft specimen gives way by hundreds of um, a rigid one by a few), and
//                        the coil cannot be resting on an end stop: within 1 mm of the rear
//                        stop (the stroke origin) only with the current at or above
//                        kRearStopLiftOff_A (1.5 A lifts the coil off in any orientation),
//                        within 1 mm of the front stop (34 mm) only with the current at or below
//                        kFrontStopRelease_A (0.25 A: the springs pull it off). detail: 0.
//   What it cannot see: an encoder glitch of at most the jump limit (a position error of that
//   many um), an encoder frozen on an end stop while the current stays in the band that may hold
//   the coil there, a current-sense reading frozen while the coil voltage stays constant (the
//   true current then stays where the reading says too).
//
// cause_present() tells Safety::clear() whether the cause is still there: the driver line, the
// low supply, the reading at the rail, the reading still frozen at a stuck value, the encoder
// still frozen where it stuck; an encoder jump is gone once it happened.
#pragma once

#include <cstdint>

#include "palp/protocol/messages.hpp"

namespace palp::fw {

inline constexpr float kSupplyMinFraction = 0.75f;
inline constexpr float kSupplyLowTime_s = 1e-3f;
/// The current-sense chain: +-5 A over the 12-bit ADC, 0 A at mid-scale (an assumption shared
/// with the plant's SensorConfig). The rail: within 1.5 codes of either end.
inline constexpr float kCurrentSenseFullScale_A = 5.0f;
inline constexpr float kCurrentSenseRail_A = kCurrentSenseFullScale_A * (1.0f - 1.5f / 2048.0f);
inline constexpr float kSenseStuckTime_s = 1e-3f;
inline constexpr float kSenseStuckSpan_V = 2.0f;
inline constexpr float kMaxCoilSpeed_m_per_s = 5.0f;
inline constexpr float kEncoderStillTime_s = 10e-3f;
inline constexpr float kEncoderStillDelta_A = 0.5f;
/// The stroke: 34 mm from the rear end stop (the stroke origin) to the front one, 1 um per count.
inline constexpr std::int32_t kStrokeCounts = 34000;
inline constexpr std::int32_t kStopZoneCounts = 1000;
inline constexpr float kRearStopLiftOff_A = 1.5f;
inline constexpr float kFrontStopRelease_A = 0.25f;

/// One tick's readings as the board took them.
struct SensorReadings {
  float i_sense_A = 0.0f;           ///< raw current-sense reading, before calibration
  float i_measured_A = 0.0f;        ///< the same, calibrated
  std::int32_t encoder_counts = 0;  ///< extended encoder position
  std::int32_t encoder_step_counts = 0;  ///< counts moved since the previous tick
  float v_applied_V = 0.0f;         ///< the coil voltage applied since the previous tick
  float supply_V = 0.0f;            ///< measured bridge supply
  bool driver_fault = false;        ///< the H-bridge driver's fault line
  float dt_s = 0.0f;                ///< control tick period
};

/// A fault a check found this tick (reason none: nothing).
struct SensorFinding {
  proto::FaultReason reason = proto::FaultReason::none;
  std::int32_t detail = 0;
};

class SensorMonitor {
 public:
  /// Params.supply_V (the nominal bridge supply) and the calibration's stroke origin.
  void configure(float supply_nominal_V, std::int32_t stroke_origin_counts);
  /// The tick's checks (see the top of the file).
  SensorFinding update(const SensorReadings& in);
  /// Whether the cause of a fault with this reason is still present (for Safety::clear()).
  bool cause_present(proto::FaultReason reason) const;

 private:
  bool coil_must_move(const SensorReadings& in) const;

  float supply_nominal_V_ = 24.0f;
  std::int32_t stroke_origin_counts_ = 0;
  bool started_ = false;

  bool driver_fault_ = false;
  float supply_low_s_ = 0.0f;
  float supply_V_ = 0.0f;

  float last_sense_A_ = 0.0f;
  float sense_same_s_ = 0.0f;   // control time the raw reading has been bit-identical
  float sense_v_min_V_ = 0.0f, sense_v_max_V_ = 0.0f;  // voltage applied meanwhile
  bool sense_at_rail_ = false;
  bool sense_stuck_ = false;

  float still_ref_A_ = 0.0f;    // measured current when the encoder count last changed
  float must_move_s_ = 0.0f;    // control time the coil has had to move without a count change
  bool encoder_jumped_ = false;
  bool encoder_stuck_ = false;
};

}  // namespace palp::fw
