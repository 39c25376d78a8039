// SPDX-License-Identifier: Apache-2.0
// What the calibration-flash tests share: distinct calibration blocks, the store on the flash
// model, and a boot (reset + a fresh store + read) the way the board does it.
#pragma once

#include <cstdint>
#include <vector>

#include "calibration_flash.hpp"
#include "flash_model.hpp"
#include "palp/fw/calibration.hpp"

namespace palp::stm32::test {

using CalibrationStore = CalibrationFlash<FlashModel>;

/// A v2 block whose values depend on `n` (so two blocks differ in many bytes).
inline std::vector<std::uint8_t> calibration_bytes(int n) {
  fw::CalibrationData d;
  d.kf_count = 2;
  d.kf_position_counts[1] = 1000 + n;
  d.kf_N_per_A[0] = 2.5f + 0.01f * static_cast<float>(n);
  d.kf_N_per_A[1] = 2.9f;
  d.current_offset_A = 0.001f * static_cast<float>(n);
  d.spring_k_N_per_m = 40.0f + static_cast<float>(n);
  d.stroke_origin_counts = -n;
  d.stroke_origin_valid = true;
  const fw::CalibrationBlock b = fw::serialize_calibration(d);
  return {b.begin(), b.end()};
}

struct Boot {
  std::vector<std::uint8_t> bytes;  // what read() returned
  fw::JournalScan scan;
};

/// A reset, then what a freshly constructed store reads (the App's boot: a 2 KB buffer).
inline Boot boot(FlashModel& model) {
  model.power_on();
  CalibrationStore store(model);
  std::vector<std::uint8_t> buffer(fw::kCalibrationMaxBlockSize);
  buffer.resize(store.read(buffer.data(), buffer.size()));
  return {buffer, store.last_scan()};
}

/// Commits `bytes` on a freshly reset part; true when stored.
inline bool commit(FlashModel& model, const std::vector<std::uint8_t>& bytes) {
  model.power_on();
  CalibrationStore store(model);
  return store.write(bytes.data(), bytes.size());
}

inline const std::vector<std::uint8_t>& erased_read() {
  static const std::vector<std::uint8_t> erased(fw::kCalibrationMaxBlockSize, 0xFF);
  return erased;
}

}  // namespace palp::stm32::test
