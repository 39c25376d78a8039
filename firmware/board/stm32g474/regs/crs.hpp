// SPDX-License-Identifier: Apache-2.0
// CRS: the clock recovery system trimming HSI48 to USB SOF. Base: stm32g474-facts.md §2;
// CR and CFGR offsets and fields: §3.3.
#pragma once

#include "register.hpp"

namespace palp::stm32::crs {

inline constexpr std::uint32_t kBase = 0x4000'2000;  // facts §2

struct Cr {  // facts §3.3 CR (0x00)
  static constexpr Field CEN{"CEN", 5, 1};
  static constexpr Field AUTOTRIMEN{"AUTOTRIMEN", 6, 1};
  static constexpr Field TRIM{"TRIM", 8, 7};
  static constexpr Field fields[] = {CEN, AUTOTRIMEN, TRIM};
  static constexpr Register reg{"CRS", "CR", kBase, 0x00, fields};
};

struct Cfgr {  // facts §3.3 CFGR (0x04)
  static constexpr Field RELOAD{"RELOAD", 0, 16};  // f_target / f_sync - 1
  static constexpr Field FELIM{"FELIM", 16, 8};
  static constexpr Field SYNCDIV{"SYNCDIV", 24, 3};
  static constexpr Field SYNCSRC{"SYNCSRC", 28, 2};  // 10 = USB SOF
  static constexpr Field fields[] = {RELOAD, FELIM, SYNCDIV, SYNCSRC};
  static constexpr Register reg{"CRS", "CFGR", kBase, 0x04, fields};

  static constexpr std::uint32_t kSyncSrcUsbSof = 0b10;
  static constexpr std::uint32_t kReloadUsbSof = 48'000'000 / 1'000 - 1;  // facts §3.3
  static constexpr std::uint32_t kFelimDefault = 0x22;                    // facts §3.3
};

}  // namespace palp::stm32::crs
