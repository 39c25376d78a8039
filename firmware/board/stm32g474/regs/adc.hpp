// SPDX-License-Identifier: Apache-2.0
// ADC1 (coil current + bridge supply, injected group) and ADC2 (six pressure channels, regular
// scan + DMA) and their common block. Bases: stm32g474-facts.md §2 (ADC1 0x5000_0000, ADC2
// 0x5000_0100, ADC1/2 common 0x5000_0300); register offsets and fields: §4.4. IER is not in the
// facts sheet (only ISR's bits): its offset and bits are from ST's SVD (peripheral ADC1, IER
// mirrors ISR bit for bit), and the SVD cross-check (tests/stm32) pins them. ADC2 is derivedFrom
// ADC1 in the SVD, so the same fields serve both; each register has one Register per ADC.
#pragma once

#include "register.hpp"

namespace palp::stm32::adc {

inline constexpr std::uint32_t kBase1 = 0x5000'0000;       // facts §2
inline constexpr std::uint32_t kBase2 = 0x5000'0100;       // facts §2
inline constexpr std::uint32_t kBaseCommon = 0x5000'0300;  // facts §2

struct Isr {  // facts §4.4 ISR (0x00), write 1 to clear
  static constexpr Field ADRDY{"ADRDY", 0, 1};
  static constexpr Field EOS{"EOS", 3, 1};
  static constexpr Field OVR{"OVR", 4, 1};
  static constexpr Field JEOC{"JEOC", 5, 1};
  static constexpr Field JEOS{"JEOS", 6, 1};
  static constexpr Field fields[] = {ADRDY, EOS, OVR, JEOC, JEOS};
  static constexpr Register adc1{"ADC1", "ISR", kBase1, 0x00, fields};
  static constexpr Register adc2{"ADC2", "ISR", kBase2, 0x00, fields};
};

struct Ier {  // SVD ADC1.IER (0x04): the interrupt enables, one per ISR flag
  static constexpr Field JEOCIE{"JEOCIE", 5, 1};
  static constexpr Field JEOSIE{"JEOSIE", 6, 1};
  static constexpr Field fields[] = {JEOCIE, JEOSIE};
  static constexpr Register adc1{"ADC1", "IER", kBase1, 0x04, fields};
};

struct Cr {  // facts §4.4 CR (0x08); ADCAL..ADEN below ADVREGEN are "rs" bits (write 1 only)
  static constexpr Field ADEN{"ADEN", 0, 1};
  static constexpr Field ADSTART{"ADSTART", 2, 1};
  static constexpr Field JADSTART{"JADSTART", 3, 1};
  static constexpr Field ADVREGEN{"ADVREGEN", 28, 1};
  static constexpr Field DEEPPWD{"DEEPPWD", 29, 1};  // 1 after reset
  static constexpr Field ADCALDIF{"ADCALDIF", 30, 1};
  static constexpr Field ADCAL{"ADCAL", 31, 1};
  static constexpr Field fields[] = {ADEN, ADSTART, JADSTART, ADVREGEN, DEEPPWD, ADCALDIF, ADCAL};
  static constexpr Register adc1{"ADC1", "CR", kBase1, 0x08, fields};
  static constexpr Register adc2{"ADC2", "CR", kBase2, 0x08, fields};
};

struct Cfgr {  // facts §4.4 CFGR (0x0C)
  static constexpr Field DMAEN{"DMAEN", 0, 1};
  static constexpr Field DMACFG{"DMACFG", 1, 1};  // 1 = circular DMA mode
  static constexpr Field RES{"RES", 3, 2};        // 00 = 12 bit
  static constexpr Field EXTSEL{"EXTSEL", 5, 5};
  static constexpr Field EXTEN{"EXTEN", 10, 2};   // 00 = software start (ADSTART)
  static constexpr Field OVRMOD{"OVRMOD", 12, 1};
  static constexpr Field CONT{"CONT", 13, 1};
  static constexpr Field fields[] = {DMAEN, DMACFG, RES, EXTSEL, EXTEN, OVRMOD, CONT};
  static constexpr Register adc1{"ADC1", "CFGR", kBase1, 0x0C, fields};
  static constexpr Register adc2{"ADC2", "CFGR", kBase2, 0x0C, fields};
};

/// Sample-time codes (facts §4.4 SMPR1/2): 3 bits per channel, channel n at bit 3·(n mod 10).
struct SampleTime {
  static constexpr std::uint32_t k24_5Cycles = 0b011;
  static constexpr std::uint32_t k47_5Cycles = 0b100;
  /// Sample cycles ×2 for each code (2.5, 6.5, ... 640.5), so integer arithmetic stays exact.
  static constexpr std::uint32_t kHalfCycles[8] = {5, 13, 25, 49, 95, 185, 495, 1281};
};

struct Smpr1 {  // facts §4.4 SMPR1 (0x14): channels 0..9
  static constexpr Field SMP3{"SMP3", 9, 3};
  static constexpr Field SMP5{"SMP5", 15, 3};
  static constexpr Field SMP6{"SMP6", 18, 3};
  static constexpr Field SMP7{"SMP7", 21, 3};
  static constexpr Field SMP8{"SMP8", 24, 3};
  static constexpr Field SMP9{"SMP9", 27, 3};
  static constexpr Field fields[] = {SMP3, SMP5, SMP6, SMP7, SMP8, SMP9};
  static constexpr Register adc2{"ADC2", "SMPR1", kBase2, 0x14, fields};
};

struct Smpr2 {  // facts §4.4 SMPR2 (0x18): channels 10..18
  static constexpr Field SMP11{"SMP11", 3, 3};
  static constexpr Field SMP12{"SMP12", 6, 3};
  static constexpr Field fields[] = {SMP11, SMP12};
  static constexpr Register adc1{"ADC1", "SMPR2", kBase1, 0x18, fields};
};

struct Sqr1 {  // facts §4.4 SQR1 (0x30): L = conversions - 1, SQ1..SQ4
  static constexpr Field L{"L", 0, 4};
  static constexpr Field SQ1{"SQ1", 6, 5};
  static constexpr Field SQ2{"SQ2", 12, 5};
  static constexpr Field SQ3{"SQ3", 18, 5};
  static constexpr Field SQ4{"SQ4", 24, 5};
  static constexpr Field fields[] = {L, SQ1, SQ2, SQ3, SQ4};
  static constexpr Register adc2{"ADC2", "SQR1", kBase2, 0x30, fields};
};

struct Sqr2 {  // facts §4.4 ("SQR2..4 hold SQ5..SQ16"); SQ5/SQ6 positions: SVD ADC1.SQR2
  static constexpr Field SQ5{"SQ5", 0, 5};
  static constexpr Field SQ6{"SQ6", 6, 5};
  static constexpr Field fields[] = {SQ5, SQ6};
  static constexpr Register adc2{"ADC2", "SQR2", kBase2, 0x34, fields};
};

struct Dr {  // facts §4.4 DR (0x40): the DMA's peripheral address
  static constexpr Field RDATA{"RDATA", 0, 16};
  static constexpr Field fields[] = {RDATA};
  static constexpr Register adc2{"ADC2", "DR", kBase2, 0x40, fields};
};

struct Jsqr {  // facts §4.4 JSQR (0x4C)
  static constexpr Field JL{"JL", 0, 2};  // conversions - 1
  static constexpr Field JEXTSEL{"JEXTSEL", 2, 5};
  static constexpr Field JEXTEN{"JEXTEN", 7, 2};  // 01 = rising edge
  static constexpr Field JSQ1{"JSQ1", 9, 5};
  static constexpr Field JSQ2{"JSQ2", 15, 5};
  static constexpr Field fields[] = {JL, JEXTSEL, JEXTEN, JSQ1, JSQ2};
  static constexpr Register adc1{"ADC1", "JSQR", kBase1, 0x4C, fields};

  static constexpr std::uint32_t kJextselTim1Trgo2 = 8;  // facts §4.4 JEXTSEL table (ADC1/2)
  static constexpr std::uint32_t kJextenRising = 0b01;
};

struct Jdr1 {  // facts §4.4 JDR1 (0x80): the first injected result (JSQ1)
  static constexpr Field JDATA1{"JDATA1", 0, 16};
  static constexpr Field fields[] = {JDATA1};
  static constexpr Register adc1{"ADC1", "JDR1", kBase1, 0x80, fields};
};

struct Jdr2 {  // facts §4.4 JDR2 (0x84): the second injected result (JSQ2)
  static constexpr Field JDATA2{"JDATA2", 0, 16};
  static constexpr Field fields[] = {JDATA2};
  static constexpr Register adc1{"ADC1", "JDR2", kBase1, 0x84, fields};
};

struct Ccr {  // facts §4.4 common CCR (0x08 in the ADC1/2 common block)
  static constexpr Field CKMODE{"CKMODE", 16, 2};  // 11 = HCLK/4
  static constexpr Field fields[] = {CKMODE};
  static constexpr Register reg{"ADC12_Common", "CCR", kBaseCommon, 0x08, fields};

  static constexpr std::uint32_t kCkmodeHclkDiv4 = 0b11;
};

}  // namespace palp::stm32::adc
