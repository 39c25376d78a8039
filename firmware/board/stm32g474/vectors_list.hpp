// SPDX-License-Identifier: Apache-2.0
// The STM32G474's external interrupts, IRQ number and name, as ST's SVD lists them
// (svd/STM32G474.svd.xz, <interrupt><name>/<value>; facts §2: "16 system entries + IRQs 0..101").
// IRQ 85 is absent from the SVD (reserved): its vector stays empty. The one definition of the
// list: vectors.cpp builds the vector table from it (handler = name + "_IRQHandler", a weak alias
// of the default handler), and the host test tests/stm32/test_vectors.cpp checks it against the
// SVD, entry by entry. Names are spelled as in the SVD (so `HRTIM_Master_IRQn_IRQHandler`,
// `Cordic_IRQHandler`), not as in CMSIS.
#pragma once

#include <cstddef>

// X(number, name) for every interrupt, in increasing number.
#define PALP_STM32G474_IRQS(X) \
  X(0, WWDG) \
  X(1, PVD_PVM) \
  X(2, RTC_TAMP_CSS_LSE) \
  X(3, RTC_WKUP) \
  X(4, FLASH) \
  X(5, RCC) \
  X(6, EXTI0) \
  X(7, EXTI1) \
  X(8, EXTI2) \
  X(9, EXTI3) \
  X(10, EXTI4) \
  X(11, DMA1_CH1) \
  X(12, DMA1_CH2) \
  X(13, DMA1_CH3) \
  X(14, DMA1_CH4) \
  X(15, DMA1_CH5) \
  X(16, DMA1_CH6) \
  X(17, DMA1_CH7) \
  X(18, ADC1_2) \
  X(19, USB_HP) \
  X(20, USB_LP) \
  X(21, FDCAN1_IT0) \
  X(22, FDCAN1_IT1) \
  X(23, EXTI9_5) \
  X(24, TIM1_BRK_TIM15) \
  X(25, TIM1_UP_TIM16) \
  X(26, TIM1_TRG_COM) \
  X(27, TIM1_CC) \
  X(28, TIM2) \
  X(29, TIM3) \
  X(30, TIM4) \
  X(31, I2C1_EV) \
  X(32, I2C1_ER) \
  X(33, I2C2_EV) \
  X(34, I2C2_ER) \
  X(35, SPI1) \
  X(36, SPI2) \
  X(37, USART1) \
  X(38, USART2) \
  X(39, USART3) \
  X(40, EXTI15_10) \
  X(41, RTC_ALARM) \
  X(42, USBWakeUP) \
  X(43, TIM8_BRK) \
  X(44, TIM8_UP) \
  X(45, TIM8_TRG_COM) \
  X(46, TIM8_CC) \
  X(47, ADC3) \
  X(48, FMC) \
  X(49, LPTIM1) \
  X(50, TIM5) \
  X(51, SPI3) \
  X(52, UART4) \
  X(53, UART5) \
  X(54, TIM6_DACUNDER) \
  X(55, TIM7) \
  X(56, DMA2_CH1) \
  X(57, DMA2_CH2) \
  X(58, DMA2_CH3) \
  X(59, DMA2_CH4) \
  X(60, DMA2_CH5) \
  X(61, ADC4) \
  X(62, ADC5) \
  X(63, UCPD1) \
  X(64, COMP1_2_3) \
  X(65, COMP4_5_6) \
  X(66, COMP7) \
  X(67, HRTIM_Master_IRQn) \
  X(68, HRTIM_TIMA_IRQn) \
  X(69, HRTIM_TIMB_IRQn) \
  X(70, HRTIM_TIMC_IRQn) \
  X(71, HRTIM_TIMD_IRQn) \
  X(72, HRTIM_TIME_IRQn) \
  X(73, HRTIM_TIM_FLT_IRQn) \
  X(74, HRTIM_TIMF_IRQn) \
  X(75, CRS) \
  X(76, SAI) \
  X(77, TIM20_BRK) \
  X(78, TIM20_UP) \
  X(79, TIM20_TRG_COM) \
  X(80, TIM20_CC) \
  X(81, FPU) \
  X(82, I2C4_EV) \
  X(83, I2C4_ER) \
  X(84, SPI4) \
  X(86, FDCAN2_IT0) \
  X(87, FDCAN2_IT1) \
  X(88, FDCAN3_IT0) \
  X(89, FDCAN3_IT1) \
  X(90, RNG) \
  X(91, LPUART) \
  X(92, I2C3_EV) \
  X(93, I2C3_ER) \
  X(94, DMAMUX_OVR) \
  X(95, QUADSPI) \
  X(96, DMA1_CH8) \
  X(97, DMA2_CH6) \
  X(98, DMA2_CH7) \
  X(99, DMA2_CH8) \
  X(100, Cordic) \
  X(101, FMAC)

namespace palp::stm32::vectors {

struct Irq {
  unsigned number;
  const char* name;  ///< as in the SVD; the handler is name + "_IRQHandler"
};

#define PALP_STM32G474_IRQ_ENTRY(number, name) Irq{number, #name},
inline constexpr Irq kIrqs[] = {PALP_STM32G474_IRQS(PALP_STM32G474_IRQ_ENTRY)};
#undef PALP_STM32G474_IRQ_ENTRY

/// Vector slots after the 16 system words: IRQ 0 to the highest listed number.
inline constexpr std::size_t kExternalSlots = 102;

constexpr bool numbers_increase_and_fit() {
  for (std::size_t k = 0; k < sizeof kIrqs / sizeof kIrqs[0]; ++k) {
    if (kIrqs[k].number >= kExternalSlots || (k > 0 && kIrqs[k].number <= kIrqs[k - 1].number)) {
      return false;
    }
  }
  return true;
}
static_assert(numbers_increase_and_fit(), "kIrqs: numbers must increase and stay below kExternalSlots");

}  // namespace palp::stm32::vectors
