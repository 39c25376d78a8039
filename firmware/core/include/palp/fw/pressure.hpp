// SPDX-License-Identifier: Apache-2.0
// The six pressure channels (paper §V-A: ELVH-L05D differential transducers on the pad's air
// channels) and the current-sense calibration.
//
// Sampling: every control tick the board hands the core one raw 12-bit ADC code per channel
// (0..4095; a larger value is clipped to 4095 and counted). The core filters and decimates them
// to the stream rate with a boxcar average: the mean of exactly `decimation` consecutive ticks
// (StreamConfigure.decimation), one output per window, windows back to back. The boxcar is the
// anti-alias filter: its first null is at the stream rate.
//
// Transfer (ASSUMPTION: a nominal ratiometric analog output, not checked against the ELVH data
// sheet here; replace the three constants below if it differs): 10 %..90 % of the ADC range
// for -FS..+FS,
//     code / 4096 = 0.5 + 0.4 * p / FS,   FS = 5 inH2O = 1245.42 Pa,
// i.e. p = (code - 2048) * FS / 1638.4 = (code - 2048) * 0.760144 Pa. The board is assumed to
// scale the sensor output so that the sensor's supply maps to the ADC's full scale (the
// ratiometric assumption). Code 2048 is 0 Pa; 409.6 is -FS; 3686.4 is +FS.
//
// Calibration (proto::Calibration): p = (p_nominal - pressure_offset_Pa) * pressure_gain per
// channel; the current sense likewise i = (i_raw - current_offset_A) * current_gain.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace palp::fw {

inline constexpr std::size_t kPressureChannelCount = 6;
/// ELVH-L05D full scale: +-5 inH2O.
inline constexpr float kPressureFullScale_Pa = 1245.42f;
inline constexpr std::uint16_t kAdcMaxCode = 4095;
/// Code of 0 Pa (50 % of 4096) and codes per full scale (40 % of 4096).
inline constexpr float kPressureZeroCode = 2048.0f;
inline constexpr float kPressureCodesPerFullScale = 1638.4f;
inline constexpr float kPressurePaPerCode = kPressureFullScale_Pa / kPressureCodesPerFullScale;

/// The nominal transfer: a (mean) ADC code to Pa, before calibration.
constexpr float nominal_pressure_Pa(float code) {
  return (code - kPressureZeroCode) * kPressurePaPerCode;
}
/// Calibration.pressure_offset_Pa / pressure_gain: (p_nominal - offset) * gain.
constexpr float apply_pressure_calibration(float nominal_Pa, float offset_Pa, float gain) {
  return (nominal_Pa - offset_Pa) * gain;
}
/// Calibration.current_offset_A / current_gain: (i_raw - offset) * gain.
constexpr float apply_current_calibration(float raw_A, float offset_A, float gain) {
  return (raw_A - offset_A) * gain;
}

struct PressureCalibration {
  std::array<float, kPressureChannelCount> offset_Pa{0, 0, 0, 0, 0, 0};
  std::array<float, kPressureChannelCount> gain{1, 1, 1, 1, 1, 1};
};

class PressureChannels {
 public:
  using Codes = std::array<std::uint16_t, kPressureChannelCount>;
  using Values = std::array<float, kPressureChannelCount>;

  explicit PressureChannels(std::uint16_t decimation_ticks = 1);

  /// Ticks per output (1..65535; 0 is taken as 1). Restarts the window.
  void set_decimation(std::uint16_t decimation_ticks);
  std::uint16_t decimation() const { return decimation_; }
  void set_calibration(const PressureCalibration& calibration) { calibration_ = calibration; }
  /// Drops the partial window: the next add() starts a new one (e.g. at stream start).
  void restart();

  /// One control tick's codes. True when this tick completed a window: pressure_Pa() and
  /// mean_code() then hold that window's values (until the next window completes).
  bool add(const Codes& codes);

  /// Last complete window, calibrated, Pa.
  const Values& pressure_Pa() const { return pressure_Pa_; }
  /// Last complete window, mean ADC code (uncalibrated).
  const Values& mean_code() const { return mean_code_; }
  /// Ticks in the current (incomplete) window.
  std::uint16_t ticks_in_window() const { return ticks_; }
  /// Codes above 4095 seen since construction (each clipped to 4095).
  std::uint32_t clipped_codes() const { return clipped_codes_; }

 private:
  PressureCalibration calibration_{};
  std::array<std::uint32_t, kPressureChannelCount> sums_{};  // <= 65535 * 4095 < 2^32
  Values pressure_Pa_{};
  Values mean_code_{};
  std::uint32_t clipped_codes_ = 0;
  std::uint16_t decimation_ = 1;
  std::uint16_t ticks_ = 0;
};

}  // namespace palp::fw
