// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/pressure.hpp"

namespace palp::fw {

PressureChannels::PressureChannels(std::uint16_t decimation_ticks) {
  set_decimation(decimation_ticks);
}

void PressureChannels::set_decimation(std::uint16_t decimation_ticks) {
  decimation_ = decimation_ticks == 0 ? std::uint16_t{1} : decimation_ticks;
  restart();
}

void PressureChannels::restart() {
  sums_ = {};
  ticks_ = 0;
}

bool PressureChannels::add(const Codes& codes) {
  for (std::size_t ch = 0; ch < kPressureChannelCount; ++ch) {
    std::uint16_t code = codes[ch];
    if (code > kAdcMaxCode) {
      code = kAdcMaxCode;
      ++clipped_codes_;
    }
    sums_[ch] += code;
  }
  if (++ticks_ < decimation_) return false;

  const std::uint32_t n = decimation_;
  for (std::size_t ch = 0; ch < kPressureChannelCount; ++ch) {
    // Whole and fractional part separately: the sum may exceed float's 24-bit mantissa.
    const std::uint32_t whole = sums_[ch] / n;
    const std::uint32_t rest = sums_[ch] % n;
    const float mean = static_cast<float>(whole) + static_cast<float>(rest) / static_cast<float>(n);
    mean_code_[ch] = mean;
    pressure_Pa_[ch] = apply_pressure_calibration(nominal_pressure_Pa(mean),
                                                  calibration_.offset_Pa[ch], calibration_.gain[ch]);
  }
  restart();
  return true;
}

}  // namespace palp::fw
