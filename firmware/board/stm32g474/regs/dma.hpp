// SPDX-License-Identifier: Apache-2.0
// DMA1 channel 1 and DMAMUX1 channel 0 (its request line): the ADC2 pressure scan into RAM.
// Bases: stm32g474-facts.md §2 (DMA1 0x4002_0000, channel n registers at +0x08 + 0x14·(n−1);
// DMAMUX1 0x4002_0800, channel CCRs from 0x00); CCR bits and the channel mapping (DMA1 channel n
// ↔ DMAMUX1 channel n−1) and request IDs: §4.5. The CNDTR/CPAR/CMAR offsets (+0x0C/+0x10/
// +0x14) and the SVD names (peripheral "DMAMUX", register "C0CR") are from ST's SVD; the
// cross-check pins them.
#pragma once

#include "register.hpp"

namespace palp::stm32::dma {

inline constexpr std::uint32_t kBaseDma1 = 0x4002'0000;    // facts §2
inline constexpr std::uint32_t kBaseDmamux1 = 0x4002'0800;  // facts §2

struct Ccr1 {  // facts §4.5 DMA_CCRx, channel 1 at 0x08 (facts §2)
  static constexpr Field EN{"EN", 0, 1};
  static constexpr Field TCIE{"TCIE", 1, 1};
  static constexpr Field DIR{"DIR", 4, 1};  // 0 = peripheral -> memory
  static constexpr Field CIRC{"CIRC", 5, 1};
  static constexpr Field PINC{"PINC", 6, 1};
  static constexpr Field MINC{"MINC", 7, 1};
  static constexpr Field PSIZE{"PSIZE", 8, 2};
  static constexpr Field MSIZE{"MSIZE", 10, 2};
  static constexpr Field PL{"PL", 12, 2};
  static constexpr Field MEM2MEM{"MEM2MEM", 14, 1};
  static constexpr Field fields[] = {EN, TCIE, DIR, CIRC, PINC, MINC, PSIZE, MSIZE, PL, MEM2MEM};
  static constexpr Register reg{"DMA1", "CCR1", kBaseDma1, 0x08, fields};

  static constexpr std::uint32_t kSize16Bit = 0b01;  // facts §4.5 (PSIZE/MSIZE 01 = 16 bit)
};

struct Cndtr1 {  // SVD DMA1.CNDTR1 (0x0C): transfers per cycle (reloaded in circular mode)
  static constexpr Field NDT{"NDT", 0, 16};
  static constexpr Field fields[] = {NDT};
  static constexpr Register reg{"DMA1", "CNDTR1", kBaseDma1, 0x0C, fields};
};

struct Cpar1 {  // SVD DMA1.CPAR1 (0x10): the peripheral address
  static constexpr Field PA{"PA", 0, 32};
  static constexpr Field fields[] = {PA};
  static constexpr Register reg{"DMA1", "CPAR1", kBaseDma1, 0x10, fields};
};

struct Cmar1 {  // SVD DMA1.CMAR1 (0x14): the memory address
  static constexpr Field MA{"MA", 0, 32};
  static constexpr Field fields[] = {MA};
  static constexpr Register reg{"DMA1", "CMAR1", kBaseDma1, 0x14, fields};
};

struct Dmamux0 {  // facts §4.5 DMAMUX1_CxCR, channel 0 (serves DMA1 channel 1)
  static constexpr Field DMAREQ_ID{"DMAREQ_ID", 0, 7};
  static constexpr Field fields[] = {DMAREQ_ID};
  static constexpr Register reg{"DMAMUX", "C0CR", kBaseDmamux1, 0x00, fields};

  static constexpr std::uint32_t kRequestAdc1 = 5;   // facts §4.5
  static constexpr std::uint32_t kRequestAdc2 = 36;  // facts §4.5
};

}  // namespace palp::stm32::dma
