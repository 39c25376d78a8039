// FLASH access control. Base: stm32g474-facts.md §2 / §1.2; ACR offset and fields: §1.2.
#pragma once

#include "register.hpp"

namespace palp::stm32::flash {

inline constexpr std::uint32_t kBase = 0x4002'2000;  // facts §2, §1.2

struct Acr {  // facts §1.2 FLASH_ACR (0x00)
  static constexpr Field LATENCY{"LATENCY", 0, 4};  // wait states
  static constexpr Field PRFTEN{"PRFTEN", 8, 1};
  static constexpr Field ICEN{"ICEN", 9, 1};
  static constexpr Field DCEN{"DCEN", 10, 1};
  static constexpr Field fields[] = {LATENCY, PRFTEN, ICEN, DCEN};
  static constexpr Register reg{"FLASH", "FLASH_ACR", kBase, 0x00, fields};
};

}  // namespace palp::stm32::flash
