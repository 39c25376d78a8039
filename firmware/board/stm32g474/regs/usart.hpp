// SPDX-License-Identifier: Apache-2.0
// LPUART1: the host link over the NUCLEO's ST-LINK virtual COM port (PA2 TX / PA3 RX,
// stm32g474-facts.md §4, pin note "PA2/PA3 = LPUART1 to ST-LINK VCP"). The facts sheet
// gives neither LPUART1's base nor its registers: base, offsets and fields below are ST's SVD
// (svd/STM32G474.svd.xz, peripheral LPUART1), and tests/stm32's SVD cross-check pins every one.
// With FIFOEN = 1 the SVD's ISR.RXNE / ISR.TXE bits read as RXFNE ("RX FIFO not empty") and
// TXFNF ("TX FIFO not full"); the names here stay the SVD's.
#pragma once

#include "register.hpp"

namespace palp::stm32::lpuart1 {

inline constexpr std::uint32_t kBase = 0x4000'8000;  // SVD LPUART1 baseAddress

struct Cr1 {  // SVD CR1 0x00
  static constexpr Field UE{"UE", 0, 1};
  static constexpr Field RE{"RE", 2, 1};
  static constexpr Field TE{"TE", 3, 1};
  static constexpr Field RXNEIE{"RXNEIE", 5, 1};  // RXFNEIE in FIFO mode; also ORE's interrupt
  static constexpr Field TXEIE{"TXEIE", 7, 1};
  static constexpr Field PS{"PS", 9, 1};
  static constexpr Field PCE{"PCE", 10, 1};
  static constexpr Field M0{"M0", 12, 1};
  static constexpr Field M1{"M1", 28, 1};  // M1:M0 = 00: 8 data bits
  static constexpr Field FIFOEN{"FIFOEN", 29, 1};
  static constexpr Field fields[] = {UE, RE, TE, RXNEIE, TXEIE, PS, PCE, M0, M1, FIFOEN};
  static constexpr Register reg{"LPUART1", "CR1", kBase, 0x00, fields};
};

struct Cr2 {  // SVD CR2 0x04
  static constexpr Field STOP{"STOP", 12, 2};  // 00 = 1 stop bit
  static constexpr Field fields[] = {STOP};
  static constexpr Register reg{"LPUART1", "CR2", kBase, 0x04, fields};
};

struct Cr3 {  // SVD CR3 0x08
  static constexpr Field EIE{"EIE", 0, 1};
  static constexpr Field OVRDIS{"OVRDIS", 12, 1};  // 0: overrun detected (ORE), kept so
  static constexpr Field fields[] = {EIE, OVRDIS};
  static constexpr Register reg{"LPUART1", "CR3", kBase, 0x08, fields};
};

struct Brr {  // SVD BRR 0x0C: 20 bits; LPUART baud = 256 x f_ck / BRR
  static constexpr Field BRR{"BRR", 0, 20};
  static constexpr Field fields[] = {BRR};
  static constexpr Register reg{"LPUART1", "BRR", kBase, 0x0C, fields};
};

struct Isr {  // SVD ISR 0x1C
  static constexpr Field FE{"FE", 1, 1};
  static constexpr Field NF{"NF", 2, 1};
  static constexpr Field ORE{"ORE", 3, 1};
  static constexpr Field RXNE{"RXNE", 5, 1};  // RXFNE in FIFO mode
  static constexpr Field TXE{"TXE", 7, 1};    // TXFNF in FIFO mode
  static constexpr Field fields[] = {FE, NF, ORE, RXNE, TXE};
  static constexpr Register reg{"LPUART1", "ISR", kBase, 0x1C, fields};
};

struct Icr {  // SVD ICR 0x20: write 1 to clear
  static constexpr Field FECF{"FECF", 1, 1};
  static constexpr Field NCF{"NCF", 2, 1};
  static constexpr Field ORECF{"ORECF", 3, 1};
  static constexpr Field fields[] = {FECF, NCF, ORECF};
  static constexpr Register reg{"LPUART1", "ICR", kBase, 0x20, fields};
};

struct Rdr {  // SVD RDR 0x24
  static constexpr Field RDR{"RDR", 0, 9};
  static constexpr Field fields[] = {RDR};
  static constexpr Register reg{"LPUART1", "RDR", kBase, 0x24, fields};
};

struct Tdr {  // SVD TDR 0x28
  static constexpr Field TDR{"TDR", 0, 9};
  static constexpr Field fields[] = {TDR};
  static constexpr Register reg{"LPUART1", "TDR", kBase, 0x28, fields};
};

struct Presc {  // SVD PRESC 0x2C: 0000 = /1
  static constexpr Field PRESCALER{"PRESCALER", 0, 4};
  static constexpr Field fields[] = {PRESCALER};
  static constexpr Register reg{"LPUART1", "PRESC", kBase, 0x2C, fields};
};

}  // namespace palp::stm32::lpuart1
