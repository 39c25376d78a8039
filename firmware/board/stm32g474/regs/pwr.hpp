// SPDX-License-Identifier: Apache-2.0
// PWR: voltage scaling and Range-1 boost. Base: stm32g474-facts.md §2; CR1 and CR5: §3.1.
#pragma once

#include "register.hpp"

namespace palp::stm32::pwr {

inline constexpr std::uint32_t kBase = 0x4000'7000;  // facts §2

struct Cr1 {  // facts §3.1 PWR_CR1 (0x00)
  static constexpr Field VOS{"VOS", 9, 2};  // 01 = Range 1 (reset value)
  static constexpr Field fields[] = {VOS};
  static constexpr Register reg{"PWR", "PWR_CR1", kBase, 0x00, fields};

  static constexpr std::uint32_t kVosRange1 = 0b01;
};

struct Cr5 {  // facts §3.1 PWR_CR5 (0x80)
  static constexpr Field R1MODE{"R1MODE", 8, 1};  // 0 = Range-1 boost, 1 = normal (reset)
  static constexpr Field fields[] = {R1MODE};
  static constexpr Register reg{"PWR", "PWR_CR5", kBase, 0x80, fields};
};

}  // namespace palp::stm32::pwr
