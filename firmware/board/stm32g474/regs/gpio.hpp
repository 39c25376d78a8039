// GPIOA: the status LED pin PA5 (NUCLEO LD2; README pin table). Base: stm32g474-facts.md §2
// (GPIOA..GPIOG at 0x4800_0000 + 0x400·n); its clock: RCC AHB2ENR.GPIOAEN (rcc.hpp).
// The register offsets and fields are not in the facts sheet: they are from ST's SVD
// (svd/STM32G474.svd.xz, peripheral GPIOA), and the SVD cross-check (tests/stm32) pins them.
#pragma once

#include "register.hpp"

namespace palp::stm32::gpio {

inline constexpr std::uint32_t kBaseA = 0x4800'0000;  // facts §2

struct ModerA {  // SVD GPIOA.MODER (0x00): 2 bits per pin, 00 input (reset for PA5), 01 output
  static constexpr Field MODER5{"MODER5", 10, 2};
  static constexpr Field fields[] = {MODER5};
  static constexpr Register reg{"GPIOA", "MODER", kBaseA, 0x00, fields};

  static constexpr std::uint32_t kOutput = 0b01;
};

struct BsrrA {  // SVD GPIOA.BSRR (0x18): write 1 to BSn sets pin n, to BRn clears it (atomic)
  static constexpr Field BS5{"BS5", 5, 1};
  static constexpr Field BR5{"BR5", 21, 1};
  static constexpr Field fields[] = {BS5, BR5};
  static constexpr Register reg{"GPIOA", "BSRR", kBaseA, 0x18, fields};
};

}  // namespace palp::stm32::gpio
