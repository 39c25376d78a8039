// SPDX-License-Identifier: Apache-2.0
// IWDG: the independent watchdog on the LSI. Base: stm32g474-facts.md §2; registers, fields and
// keys: §4.7.
#pragma once

#include "register.hpp"

namespace palp::stm32::iwdg {

inline constexpr std::uint32_t kBase = 0x4000'3000;  // facts §2

struct Kr {  // facts §4.7 KR 0x00
  static constexpr Field KEY{"KEY", 0, 16};
  static constexpr Field fields[] = {KEY};
  static constexpr Register reg{"IWDG", "KR", kBase, 0x00, fields};

  static constexpr std::uint32_t kStart = 0xCCCC;
  static constexpr std::uint32_t kUnlock = 0x5555;
  static constexpr std::uint32_t kReload = 0xAAAA;
};

struct Pr {  // facts §4.7 PR 0x04: 0 = /4 ... 6 = /256
  static constexpr Field PR{"PR", 0, 3};
  static constexpr Field fields[] = {PR};
  static constexpr Register reg{"IWDG", "PR", kBase, 0x04, fields};
};

struct Rlr {  // facts §4.7 RLR 0x08: RL[11:0]
  static constexpr Field RL{"RL", 0, 12};
  static constexpr Field fields[] = {RL};
  static constexpr Register reg{"IWDG", "RLR", kBase, 0x08, fields};
};

struct Sr {  // facts §4.7 SR 0x0C: an update of PR/RLR/WINR in progress
  static constexpr Field PVU{"PVU", 0, 1};
  static constexpr Field RVU{"RVU", 1, 1};
  static constexpr Field WVU{"WVU", 2, 1};
  static constexpr Field fields[] = {PVU, RVU, WVU};
  static constexpr Register reg{"IWDG", "SR", kBase, 0x0C, fields};
};

}  // namespace palp::stm32::iwdg
