// SPDX-License-Identifier: Apache-2.0
// RCC: the registers the clock init uses. Base address: stm32g474-facts.md §2; register offsets
// and fields: §3.1 (RCC_CR, RCC_CFGR, RCC_PLLCFGR, RCC_CCIPR, RCC_CRRCR, enable registers);
// APB1ENR1.PWREN/CRSEN: §2 (bus / RCC enable column).
#pragma once

#include "register.hpp"

namespace palp::stm32::rcc {

inline constexpr std::uint32_t kBase = 0x4002'1000;  // facts §2

struct Cr {  // facts §3.1 RCC_CR (0x00)
  static constexpr Field HSION{"HSION", 8, 1};
  static constexpr Field HSIRDY{"HSIRDY", 10, 1};
  static constexpr Field PLLON{"PLLON", 24, 1};
  static constexpr Field PLLRDY{"PLLRDY", 25, 1};
  static constexpr Field fields[] = {HSION, HSIRDY, PLLON, PLLRDY};
  static constexpr Register reg{"RCC", "RCC_CR", kBase, 0x00, fields};
};

struct Cfgr {  // facts §3.1 RCC_CFGR (0x08)
  static constexpr Field SW{"SW", 0, 2};      // 11 = PLL
  static constexpr Field SWS{"SWS", 2, 2};    // 11 = PLL
  static constexpr Field HPRE{"HPRE", 4, 4};  // 0000 = /1, 1000 = /2
  static constexpr Field PPRE1{"PPRE1", 8, 3};
  static constexpr Field PPRE2{"PPRE2", 11, 3};
  static constexpr Field fields[] = {SW, SWS, HPRE, PPRE1, PPRE2};
  static constexpr Register reg{"RCC", "RCC_CFGR", kBase, 0x08, fields};

  static constexpr std::uint32_t kSwHsi16 = 0b01;
  static constexpr std::uint32_t kSwPll = 0b11;
  static constexpr std::uint32_t kHpreDiv1 = 0b0000;
  static constexpr std::uint32_t kHpreDiv2 = 0b1000;
};

struct Pllcfgr {  // facts §3.1 RCC_PLLCFGR (0x0C)
  static constexpr Field PLLSRC{"PLLSRC", 0, 2};  // 10 = HSI16
  static constexpr Field PLLM{"PLLM", 4, 4};      // M - 1
  static constexpr Field PLLN{"PLLN", 8, 7};      // N (8..127)
  static constexpr Field PLLPEN{"PLLPEN", 16, 1};
  static constexpr Field PLLQEN{"PLLQEN", 20, 1};
  static constexpr Field PLLREN{"PLLREN", 24, 1};
  static constexpr Field PLLR{"PLLR", 25, 2};  // 00 = /2, 01 = /4, 10 = /6, 11 = /8
  static constexpr Field fields[] = {PLLSRC, PLLM, PLLN, PLLPEN, PLLQEN, PLLREN, PLLR};
  static constexpr Register reg{"RCC", "RCC_PLLCFGR", kBase, 0x0C, fields};

  static constexpr std::uint32_t kSrcHsi16 = 0b10;
};

struct Apb1enr1 {  // facts §3.1 enable registers (0x58); bits: §2
  static constexpr Field CRSEN{"CRSEN", 8, 1};
  static constexpr Field PWREN{"PWREN", 28, 1};
  static constexpr Field TIM2EN{"TIM2EN", 0, 1};  // facts §2 (TIM2 row)
  static constexpr Field TIM5EN{"TIM5EN", 3, 1};  // facts §2 (TIM5 row)
  static constexpr Field USBEN{"USBEN", 23, 1};   // facts §2 (USB row)
  static constexpr Field fields[] = {CRSEN, PWREN, TIM2EN, TIM5EN, USBEN};
  static constexpr Register reg{"RCC", "RCC_APB1ENR1", kBase, 0x58, fields};
};

struct Ccipr {  // facts §3.1 RCC_CCIPR (0x88)
  static constexpr Field CLK48SEL{"CLK48SEL", 26, 2};  // 00 = HSI48 (reset), 10 = PLL "Q"
  // LPUART1's kernel clock (link_uart.hpp); not in the facts sheet: SVD bits 11:10,
  // 00 = PCLK, 01 = SYSCLK, 10 = HSI16, 11 = LSE.
  static constexpr Field LPUART1SEL{"LPUART1SEL", 10, 2};
  static constexpr Field fields[] = {CLK48SEL, LPUART1SEL};
  static constexpr Register reg{"RCC", "RCC_CCIPR", kBase, 0x88, fields};

  static constexpr std::uint32_t kClk48Hsi48 = 0b00;
  static constexpr std::uint32_t kLpuart1Pclk = 0b00;
};

struct Crrcr {  // facts §3.1 RCC_CRRCR (0x98)
  static constexpr Field HSI48ON{"HSI48ON", 0, 1};
  static constexpr Field HSI48RDY{"HSI48RDY", 1, 1};
  static constexpr Field fields[] = {HSI48ON, HSI48RDY};
  static constexpr Register reg{"RCC", "RCC_CRRCR", kBase, 0x98, fields};
};

struct Ahb2enr {  // facts §3.1 enable registers (0x4C); bits: §2 (GPIOxEN bits 0..6)
  static constexpr Field GPIOAEN{"GPIOAEN", 0, 1};
  static constexpr Field GPIOBEN{"GPIOBEN", 1, 1};
  static constexpr Field GPIOCEN{"GPIOCEN", 2, 1};
  static constexpr Field ADC12EN{"ADC12EN", 13, 1};  // facts §2: one bit for ADC1 + ADC2
  static constexpr Field fields[] = {GPIOAEN, GPIOBEN, GPIOCEN, ADC12EN};
  static constexpr Register reg{"RCC", "RCC_AHB2ENR", kBase, 0x4C, fields};
};

struct Apb2enr {  // facts §3.1 enable registers (0x60); TIM1EN: §2 (TIM1 row)
  static constexpr Field TIM1EN{"TIM1EN", 11, 1};
  static constexpr Field fields[] = {TIM1EN};
  static constexpr Register reg{"RCC", "RCC_APB2ENR", kBase, 0x60, fields};
};

// LPUART1's clock (link_uart.hpp). Not in the facts sheet: offset and bits are ST's SVD
// (RCC_APB1ENR2 0x5C; RCC_CCIPR.LPUART1SEL is in Ccipr above), pinned by the SVD cross-check.
struct Apb1enr2 {  // SVD RCC_APB1ENR2 (0x5C)
  static constexpr Field LPUART1EN{"LPUART1EN", 0, 1};
  static constexpr Field fields[] = {LPUART1EN};
  static constexpr Register reg{"RCC", "RCC_APB1ENR2", kBase, 0x5C, fields};
};

// DMA clocks (adc.hpp). AHB1ENR: facts §3.1 (0x48), bits §2 (DMA1 / DMAMUX1 rows).
struct Ahb1enr {
  static constexpr Field DMA1EN{"DMA1EN", 0, 1};
  static constexpr Field DMAMUX1EN{"DMAMUX1EN", 2, 1};
  static constexpr Field fields[] = {DMA1EN, DMAMUX1EN};
  static constexpr Register reg{"RCC", "RCC_AHB1ENR", kBase, 0x48, fields};
};

}  // namespace palp::stm32::rcc
