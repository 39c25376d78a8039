// SPDX-License-Identifier: Apache-2.0
// GPIOA/B/C: the status LED pin PA5 (NUCLEO LD2) and every pin of the README pin table
// (pins.hpp). Base: stm32g474-facts.md §2
// (GPIOA..GPIOG at 0x4800_0000 + 0x400·n); clocks: RCC AHB2ENR.GPIOxEN (rcc.hpp).
// The register offsets and fields are not in the facts sheet: they are from ST's SVD
// (svd/STM32G474.svd.xz, peripheral GPIOA), and the SVD cross-check (tests/stm32) pins them.
#pragma once

#include "register.hpp"

namespace palp::stm32::gpio {

inline constexpr std::uint32_t kBaseA = 0x4800'0000;  // facts §2

inline constexpr std::uint32_t kBaseB = 0x4800'0400;  // facts §2
inline constexpr std::uint32_t kBaseC = 0x4800'0800;  // facts §2

// Every pin's field of the per-pin registers (SVD names; the same on every port), so the SVD
// cross-check pins the position formula for all 16 pins: MODER/OSPEEDR/PUPDR 2 bits at 2·n,
// OTYPER 1 bit at n, AFRL 4 bits at 4·n (pins 0..7), AFRH 4 bits at 4·(n − 8) (pins 8..15).
inline constexpr Field kModerFields[] = {
    {"MODER0", 0, 2}, {"MODER1", 2, 2}, {"MODER2", 4, 2}, {"MODER3", 6, 2}, {"MODER4", 8, 2},
    {"MODER5", 10, 2}, {"MODER6", 12, 2}, {"MODER7", 14, 2}, {"MODER8", 16, 2}, {"MODER9", 18, 2},
    {"MODER10", 20, 2}, {"MODER11", 22, 2}, {"MODER12", 24, 2}, {"MODER13", 26, 2},
    {"MODER14", 28, 2}, {"MODER15", 30, 2},
};
inline constexpr Field kOtyperFields[] = {
    {"OT0", 0, 1}, {"OT1", 1, 1}, {"OT2", 2, 1}, {"OT3", 3, 1}, {"OT4", 4, 1}, {"OT5", 5, 1},
    {"OT6", 6, 1}, {"OT7", 7, 1}, {"OT8", 8, 1}, {"OT9", 9, 1}, {"OT10", 10, 1}, {"OT11", 11, 1},
    {"OT12", 12, 1}, {"OT13", 13, 1}, {"OT14", 14, 1}, {"OT15", 15, 1},
};
inline constexpr Field kOspeedrFields[] = {
    {"OSPEEDR0", 0, 2}, {"OSPEEDR1", 2, 2}, {"OSPEEDR2", 4, 2}, {"OSPEEDR3", 6, 2},
    {"OSPEEDR4", 8, 2}, {"OSPEEDR5", 10, 2}, {"OSPEEDR6", 12, 2}, {"OSPEEDR7", 14, 2},
    {"OSPEEDR8", 16, 2}, {"OSPEEDR9", 18, 2}, {"OSPEEDR10", 20, 2}, {"OSPEEDR11", 22, 2},
    {"OSPEEDR12", 24, 2}, {"OSPEEDR13", 26, 2}, {"OSPEEDR14", 28, 2}, {"OSPEEDR15", 30, 2},
};
inline constexpr Field kPupdrFields[] = {
    {"PUPDR0", 0, 2}, {"PUPDR1", 2, 2}, {"PUPDR2", 4, 2}, {"PUPDR3", 6, 2}, {"PUPDR4", 8, 2},
    {"PUPDR5", 10, 2}, {"PUPDR6", 12, 2}, {"PUPDR7", 14, 2}, {"PUPDR8", 16, 2}, {"PUPDR9", 18, 2},
    {"PUPDR10", 20, 2}, {"PUPDR11", 22, 2}, {"PUPDR12", 24, 2}, {"PUPDR13", 26, 2},
    {"PUPDR14", 28, 2}, {"PUPDR15", 30, 2},
};
inline constexpr Field kAfrlFields[] = {
    {"AFRL0", 0, 4}, {"AFRL1", 4, 4}, {"AFRL2", 8, 4}, {"AFRL3", 12, 4}, {"AFRL4", 16, 4},
    {"AFRL5", 20, 4}, {"AFRL6", 24, 4}, {"AFRL7", 28, 4},
};
inline constexpr Field kAfrhFields[] = {
    {"AFRH8", 0, 4}, {"AFRH9", 4, 4}, {"AFRH10", 8, 4}, {"AFRH11", 12, 4}, {"AFRH12", 16, 4},
    {"AFRH13", 20, 4}, {"AFRH14", 24, 4}, {"AFRH15", 28, 4},
};

struct ModerA {  // SVD GPIOA.MODER (0x00): 2 bits per pin, 00 input (reset for PA5), 01 output
  static constexpr Field MODER5 = kModerFields[5];
  static constexpr Register reg{"GPIOA", "MODER", kBaseA, 0x00, kModerFields};

  static constexpr std::uint32_t kOutput = 0b01;
};

struct BsrrA {  // SVD GPIOA.BSRR (0x18): write 1 to BSn sets pin n, to BRn clears it (atomic)
  static constexpr Field BS5{"BS5", 5, 1};
  static constexpr Field BR5{"BR5", 21, 1};
  static constexpr Field fields[] = {BS5, BR5};
  static constexpr Register reg{"GPIOA", "BSRR", kBaseA, 0x18, fields};
};

/// The registers pins.hpp configures, per port (SVD GPIOx, offsets 0x00..0x24). GPIOA's MODER is
/// ModerA above (the bring-up image uses it).
struct PortRegs {
  const Register& moder;
  const Register& otyper;
  const Register& ospeedr;
  const Register& pupdr;
  const Register& afrl;
  const Register& afrh;
};

#define PALP_GPIO_PORT_REGS(PORT, BASE)                                                  \
  struct Port##PORT {                                                                    \
    static constexpr Register otyper{"GPIO" #PORT, "OTYPER", BASE, 0x04, kOtyperFields};  \
    static constexpr Register ospeedr{"GPIO" #PORT, "OSPEEDR", BASE, 0x08, kOspeedrFields}; \
    static constexpr Register pupdr{"GPIO" #PORT, "PUPDR", BASE, 0x0C, kPupdrFields};     \
    static constexpr Register afrl{"GPIO" #PORT, "AFRL", BASE, 0x20, kAfrlFields};        \
    static constexpr Register afrh{"GPIO" #PORT, "AFRH", BASE, 0x24, kAfrhFields};        \
  };
PALP_GPIO_PORT_REGS(A, kBaseA)
PALP_GPIO_PORT_REGS(B, kBaseB)
PALP_GPIO_PORT_REGS(C, kBaseC)
#undef PALP_GPIO_PORT_REGS

// The board's own GPIO lines (stm_board.hpp; README §3): the nFAULT input PC10, the contact line
// PC6 and the driver enable PC11 (outputs), the status LED PA5 (BsrrA above).
struct IdrC {  // SVD GPIOC.IDR (0x10): the pins' input levels
  static constexpr Field IDR10{"IDR10", 10, 1};
  static constexpr Field fields[] = {IDR10};
  static constexpr Register reg{"GPIOC", "IDR", kBaseC, 0x10, fields};
};

struct BsrrC {  // SVD GPIOC.BSRR (0x18): write 1 to BSn sets pin n, to BRn clears it (atomic)
  static constexpr Field BS6{"BS6", 6, 1};
  static constexpr Field BS11{"BS11", 11, 1};
  static constexpr Field BR6{"BR6", 22, 1};
  static constexpr Field BR11{"BR11", 27, 1};
  static constexpr Field fields[] = {BS6, BS11, BR6, BR11};
  static constexpr Register reg{"GPIOC", "BSRR", kBaseC, 0x18, fields};
};

struct ModerB {  // SVD GPIOB.MODER
  static constexpr Register reg{"GPIOB", "MODER", kBaseB, 0x00, kModerFields};
};
struct ModerC {  // SVD GPIOC.MODER
  static constexpr Register reg{"GPIOC", "MODER", kBaseC, 0x00, kModerFields};
};

inline constexpr PortRegs kPortA{ModerA::reg, PortA::otyper, PortA::ospeedr, PortA::pupdr,
                                 PortA::afrl, PortA::afrh};
inline constexpr PortRegs kPortB{ModerB::reg, PortB::otyper, PortB::ospeedr, PortB::pupdr,
                                 PortB::afrl, PortB::afrh};
inline constexpr PortRegs kPortC{ModerC::reg, PortC::otyper, PortC::ospeedr, PortC::pupdr,
                                 PortC::afrl, PortC::afrh};

}  // namespace palp::stm32::gpio
