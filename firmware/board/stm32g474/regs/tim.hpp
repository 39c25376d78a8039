// SPDX-License-Identifier: Apache-2.0
// TIM1 (advanced timer: the H-bridge PWM and the ADC trigger), TIM2 (32-bit: the quadrature
// encoder) and TIM5 (32-bit: the board's free-running microsecond clock). Bases: stm32g474-facts.md
// §2; offsets: §4.1; TIM1 fields: §4.2; TIM2/TIM5 fields: §4.3 (both 32-bit). TIM5 is derivedFrom
// TIM2 in the SVD, so its registers keep TIM2's SVD names (TIM2_CR1, ...) under peripheral TIM5.
// Register and field names as in the SVD: TIM1_CR1, ..., TIM1_CCMR1_Alternate (the output-compare
// view of CCMR1); the 4th bit of a split field is the SVD's `_1` field (OC1M_1 = OC1M[3] at bit
// 16, MMS_1 = MMS[3] at bit 25, SMS_1 = SMS[3] at bit 16; facts §4.2, §4.3). Widths of ARR/CCRx
// (20 bits on TIM1: dithering, facts §4.2 CR1.DITHEN) follow the SVD; the code writes < 2^16.
#pragma once

#include "register.hpp"

namespace palp::stm32::tim {

inline constexpr std::uint32_t kTim1Base = 0x4001'2C00;  // facts §2
inline constexpr std::uint32_t kTim2Base = 0x4000'0000;  // facts §2
inline constexpr std::uint32_t kTim5Base = 0x4000'0C00;  // facts §2

/// CR1 fields, the same on TIM1 and TIM2 (facts §4.2 CR1).
struct Cr1Fields {
  static constexpr Field CEN{"CEN", 0, 1};
  static constexpr Field CMS{"CMS", 5, 2};  // 00 edge, 01/10/11 centre-aligned mode 1/2/3
  static constexpr Field ARPE{"ARPE", 7, 1};
  static constexpr Field CKD{"CKD", 8, 2};  // t_DTS = 2^CKD t_CK_INT
  static constexpr Field fields[] = {CEN, CMS, ARPE, CKD};
};

/// EGR.UG (facts §4.2 enable notes: set UG once after configuring).
struct EgrFields {
  static constexpr Field UG{"UG", 0, 1};
  static constexpr Field fields[] = {UG};
};

}  // namespace palp::stm32::tim

namespace palp::stm32::tim1 {

using tim::kTim1Base;

struct Cr1 : tim::Cr1Fields {  // facts §4.1 CR1 0x00, §4.2
  static constexpr Register reg{"TIM1", "TIM1_CR1", kTim1Base, 0x00, fields};
};

struct Cr2 {  // facts §4.1 CR2 0x04, §4.2 (OISx, MMS2)
  static constexpr Field OIS1{"OIS1", 8, 1};
  static constexpr Field OIS1N{"OIS1N", 9, 1};
  static constexpr Field OIS2{"OIS2", 10, 1};
  static constexpr Field OIS2N{"OIS2N", 11, 1};
  static constexpr Field MMS2{"MMS2", 20, 4};
  static constexpr Field fields[] = {OIS1, OIS1N, OIS2, OIS2N, MMS2};
  static constexpr Register reg{"TIM1", "TIM1_CR2", kTim1Base, 0x04, fields};

  static constexpr std::uint32_t kMms2Oc4Ref = 0b0111;  // facts §4.2 TRGO2 table
};

/// PWM mode codes of OCxM (4 bits: OCxM[2:0] + OCxM[3]; facts §4.2 CCMR1).
inline constexpr std::uint32_t kOcPwm1 = 0b0110;
inline constexpr std::uint32_t kOcPwm2 = 0b0111;

struct Ccmr1 {  // facts §4.1 CCMR1 0x18, §4.2 (output mode)
  static constexpr Field CC1S{"CC1S", 0, 2};
  static constexpr Field OC1PE{"OC1PE", 3, 1};
  static constexpr Field OC1M{"OC1M", 4, 3};
  static constexpr Field CC2S{"CC2S", 8, 2};
  static constexpr Field OC2PE{"OC2PE", 11, 1};
  static constexpr Field OC2M{"OC2M", 12, 3};
  static constexpr Field OC1M_3{"OC1M_1", 16, 1};  // OC1M[3]
  static constexpr Field OC2M_3{"OC2M_1", 24, 1};  // OC2M[3]
  static constexpr Field fields[] = {CC1S, OC1PE, OC1M, CC2S, OC2PE, OC2M, OC1M_3, OC2M_3};
  static constexpr Register reg{"TIM1", "TIM1_CCMR1_Alternate", kTim1Base, 0x18, fields};
};

struct Ccmr2 {  // facts §4.1 CCMR2 0x1C, §4.2 ("CH2 same at +8": CH3 at 0, CH4 at 8)
  static constexpr Field CC4S{"CC4S", 8, 2};
  static constexpr Field OC4PE{"OC4PE", 11, 1};
  static constexpr Field OC4M{"OC4M", 12, 3};
  static constexpr Field OC4M_3{"OC4M_1", 24, 1};  // OC4M[3]
  static constexpr Field fields[] = {CC4S, OC4PE, OC4M, OC4M_3};
  static constexpr Register reg{"TIM1", "TIM1_CCMR2_Alternate", kTim1Base, 0x1C, fields};
};

struct Ccer {  // facts §4.1 CCER 0x20, §4.2
  static constexpr Field CC1E{"CC1E", 0, 1};
  static constexpr Field CC1P{"CC1P", 1, 1};
  static constexpr Field CC1NE{"CC1NE", 2, 1};
  static constexpr Field CC1NP{"CC1NP", 3, 1};
  static constexpr Field CC2E{"CC2E", 4, 1};
  static constexpr Field CC2P{"CC2P", 5, 1};
  static constexpr Field CC2NE{"CC2NE", 6, 1};
  static constexpr Field CC2NP{"CC2NP", 7, 1};
  static constexpr Field CC4E{"CC4E", 12, 1};
  static constexpr Field fields[] = {CC1E, CC1P, CC1NE, CC1NP, CC2E, CC2P, CC2NE, CC2NP, CC4E};
  static constexpr Register reg{"TIM1", "TIM1_CCER", kTim1Base, 0x20, fields};
};

struct Psc {  // facts §4.1 PSC 0x28
  static constexpr Field PSC{"PSC", 0, 16};
  static constexpr Field fields[] = {PSC};
  static constexpr Register reg{"TIM1", "TIM1_PSC", kTim1Base, 0x28, fields};
};

struct Arr {  // facts §4.1 ARR 0x2C
  static constexpr Field ARR{"ARR", 0, 20};
  static constexpr Field fields[] = {ARR};
  static constexpr Register reg{"TIM1", "TIM1_ARR", kTim1Base, 0x2C, fields};
};

struct Rcr {  // facts §4.1 RCR 0x30, §4.2 enable notes (RCR 0: update at top and bottom)
  static constexpr Field REP{"REP", 0, 16};
  static constexpr Field fields[] = {REP};
  static constexpr Register reg{"TIM1", "TIM1_RCR", kTim1Base, 0x30, fields};
};

struct Ccr1 {  // facts §4.1 CCR1 0x34
  static constexpr Field CCR1{"CCR1", 0, 20};
  static constexpr Field fields[] = {CCR1};
  static constexpr Register reg{"TIM1", "TIM1_CCR1", kTim1Base, 0x34, fields};
};

struct Ccr2 {  // facts §4.1 CCR2 0x38
  static constexpr Field CCR2{"CCR2", 0, 20};
  static constexpr Field fields[] = {CCR2};
  static constexpr Register reg{"TIM1", "TIM1_CCR2", kTim1Base, 0x38, fields};
};

struct Ccr4 {  // facts §4.1 CCR4 0x40
  static constexpr Field CCR4{"CCR4", 0, 20};
  static constexpr Field fields[] = {CCR4};
  static constexpr Register reg{"TIM1", "TIM1_CCR4", kTim1Base, 0x40, fields};
};

struct Bdtr {  // facts §4.1 BDTR 0x44, §4.2
  static constexpr Field DTG{"DTG", 0, 8};
  static constexpr Field LOCK{"LOCK", 8, 2};
  static constexpr Field OSSI{"OSSI", 10, 1};
  static constexpr Field OSSR{"OSSR", 11, 1};
  static constexpr Field MOE{"MOE", 15, 1};
  static constexpr Field fields[] = {DTG, LOCK, OSSI, OSSR, MOE};
  static constexpr Register reg{"TIM1", "TIM1_BDTR", kTim1Base, 0x44, fields};
};

struct Egr : tim::EgrFields {  // facts §4.1 EGR 0x14
  static constexpr Register reg{"TIM1", "TIM1_EGR", kTim1Base, 0x14, fields};
};

}  // namespace palp::stm32::tim1

namespace palp::stm32::tim2 {

using tim::kTim2Base;

struct Cr1 : tim::Cr1Fields {  // facts §4.1 CR1 0x00
  static constexpr Register reg{"TIM2", "TIM2_CR1", kTim2Base, 0x00, fields};
};

struct Smcr {  // facts §4.1 SMCR 0x08, §4.3
  static constexpr Field SMS{"SMS", 0, 3};
  static constexpr Field SMS_3{"SMS_1", 16, 1};  // SMS[3]
  static constexpr Field fields[] = {SMS, SMS_3};
  static constexpr Register reg{"TIM2", "TIM2_SMCR", kTim2Base, 0x08, fields};

  static constexpr std::uint32_t kEncoderMode3 = 0b0011;  // x4, both TI1 and TI2 edges
};

struct Ccmr1 {  // facts §4.1 CCMR1 0x18, §4.3 (input mode)
  static constexpr Field CC1S{"CC1S", 0, 2};   // 01 = IC1 <- TI1
  static constexpr Field IC1F{"IC1F", 4, 4};
  static constexpr Field CC2S{"CC2S", 8, 2};   // 01 = IC2 <- TI2
  static constexpr Field IC2F{"IC2F", 12, 4};
  static constexpr Field fields[] = {CC1S, IC1F, CC2S, IC2F};
  static constexpr Register reg{"TIM2", "TIM2_CCMR1", kTim2Base, 0x18, fields};

  static constexpr std::uint32_t kCcInputOwnTi = 0b01;
};

struct Ccer {  // facts §4.1 CCER 0x20, §4.3 (CCxP inverts a channel: reverses the count)
  static constexpr Field CC1P{"CC1P", 1, 1};
  static constexpr Field CC1NP{"CC1NP", 3, 1};
  static constexpr Field CC2P{"CC2P", 5, 1};
  static constexpr Field CC2NP{"CC2NP", 7, 1};
  static constexpr Field fields[] = {CC1P, CC1NP, CC2P, CC2NP};
  static constexpr Register reg{"TIM2", "TIM2_CCER", kTim2Base, 0x20, fields};
};

struct Cnt {  // facts §4.1 CNT 0x24 (bit 31 is the counter's MSB while CR1.UIFREMAP = 0)
  static constexpr Field CNT{"CNT", 0, 31};
  static constexpr Field fields[] = {CNT};
  static constexpr Register reg{"TIM2", "TIM2_CNT", kTim2Base, 0x24, fields};
};

struct Arr {  // facts §4.1 ARR 0x2C, §4.3 (0xFFFF_FFFF)
  static constexpr Field ARR{"ARR", 0, 32};
  static constexpr Field fields[] = {ARR};
  static constexpr Register reg{"TIM2", "TIM2_ARR", kTim2Base, 0x2C, fields};
};

struct Egr : tim::EgrFields {  // facts §4.1 EGR 0x14
  static constexpr Register reg{"TIM2", "TIM2_EGR", kTim2Base, 0x14, fields};
};

}  // namespace palp::stm32::tim2

namespace palp::stm32::tim5 {

using tim::kTim5Base;

// The µs clock (stm_board.hpp): PSC = 170 - 1, ARR = 0xFFFF_FFFF, counting up from UG.
struct Cr1 : tim::Cr1Fields {  // facts §4.1 CR1 0x00
  static constexpr Register reg{"TIM5", "TIM2_CR1", kTim5Base, 0x00, fields};
};

struct Egr : tim::EgrFields {  // facts §4.1 EGR 0x14
  static constexpr Register reg{"TIM5", "TIM2_EGR", kTim5Base, 0x14, fields};
};

struct Cnt {  // facts §4.1 CNT 0x24; the count's 32 bits (bit 31 is CNT's MSB while UIFREMAP = 0)
  static constexpr Field CNT{"CNT", 0, 31};
  static constexpr Field fields[] = {CNT};
  static constexpr Register reg{"TIM5", "TIM2_CNT", kTim5Base, 0x24, fields};
};

struct Psc {  // facts §4.1 PSC 0x28: f_cnt = f_tim / (PSC + 1)
  static constexpr Field PSC{"PSC", 0, 16};
  static constexpr Field fields[] = {PSC};
  static constexpr Register reg{"TIM5", "TIM2_PSC", kTim5Base, 0x28, fields};
};

struct Arr {  // facts §4.1 ARR 0x2C, §4.3 (32-bit: 0xFFFF_FFFF)
  static constexpr Field ARR{"ARR", 0, 32};
  static constexpr Field fields[] = {ARR};
  static constexpr Register reg{"TIM5", "TIM2_ARR", kTim5Base, 0x2C, fields};
};

}  // namespace palp::stm32::tim5
