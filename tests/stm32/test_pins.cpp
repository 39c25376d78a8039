// SPDX-License-Identifier: Apache-2.0
// The pin table (firmware/board/stm32g474/pins.hpp) on a host register file: after init, each
// pin's mode, AF, pull and output type are COMPUTED back from MODER/AFRL/AFRH/PUPDR/OTYPER and
// compared with the table, which is compared with the README's pin table; pins outside the table
// keep their reset state.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <set>
#include <utility>

#include "adc.hpp"
#include "pins.hpp"
#include "register_file.hpp"

namespace palp::stm32::pins_test {
namespace {

using pins::Mode;
using pins::Port;
using test::RegisterFile;

std::uint32_t bits(const RegisterFile& rf, const Register& reg, std::uint32_t position,
                   std::uint32_t width) {
  return (rf.peek(reg) >> position) & ((1u << width) - 1u);
}

// RM0440 reset value of GPIOA_MODER (PA13/PA14 SWD in AF, PA15 JTDI in AF; others analog).
constexpr std::uint32_t kModerAReset = 0xABFF'FFFF;

RegisterFile initialised() {
  RegisterFile rf;
  rf.poke(gpio::ModerA::reg, kModerAReset);
  rf.poke(gpio::ModerB::reg, 0xFFFF'FEBF);  // RM0440: PB3/PB4 JTAG in AF
  rf.poke(gpio::ModerC::reg, 0xFFFF'FFFF);
  pins::init(rf, pins::kPins);
  return rf;
}

TEST(Stm32Pins, TheTableHasNoPinTwice) {
  std::set<std::pair<Port, std::uint8_t>> seen;
  for (const pins::Pin& pin : pins::kPins) {
    EXPECT_LT(pin.number, 16u) << pin.signal;
    EXPECT_TRUE(seen.insert({pin.port, pin.number}).second) << pin.signal << " twice";
  }
  EXPECT_EQ(seen.size(), 23u);  // README §3: 21 rows + PA2/PA3 for the host link
  std::array<pins::Pin, 2> twice = {pins::kPins[0], pins::kPins[0]};
  EXPECT_FALSE(pins::no_pin_twice(twice));
}

TEST(Stm32Pins, AfterInitEachPinHasTheTablesModeAfAndPull) {
  const RegisterFile rf = initialised();
  for (const pins::Pin& pin : pins::kPins) {
    const gpio::PortRegs& regs = pins::port_regs(pin.port);
    const std::uint32_t n = pin.number;
    EXPECT_EQ(bits(rf, regs.moder, 2 * n, 2), static_cast<std::uint32_t>(pin.mode)) << pin.signal;
    EXPECT_EQ(bits(rf, regs.pupdr, 2 * n, 2), static_cast<std::uint32_t>(pin.pull)) << pin.signal;
    EXPECT_EQ(bits(rf, regs.otyper, n, 1), 0u) << pin.signal;  // push-pull
    if (pin.mode == Mode::alternate) {
      const Register& afr = n < 8 ? regs.afrl : regs.afrh;
      EXPECT_EQ(bits(rf, afr, 4 * (n % 8), 4), pin.af) << pin.signal;
    }
  }
}

TEST(Stm32Pins, ReadmeRowsComeBackFromTheRegisters) {
  const RegisterFile rf = initialised();
  // Known answers from README §3, read straight from the port registers.
  EXPECT_EQ(bits(rf, gpio::ModerA::reg, 2 * 8, 2), 0b10u);  // PA8 TIM1_CH1 AF
  EXPECT_EQ(bits(rf, gpio::PortA::afrh, 4 * 0, 4), 6u);     // PA8 AF6
  EXPECT_EQ(bits(rf, gpio::PortB::afrh, 4 * 5, 4), 6u);     // PB13 AF6 (CH1N)
  EXPECT_EQ(bits(rf, gpio::PortB::afrh, 4 * 6, 4), 6u);     // PB14 AF6 (CH2N)
  EXPECT_EQ(bits(rf, gpio::PortA::afrl, 4 * 0, 4), 1u);     // PA0 AF1 (TIM2_CH1)
  EXPECT_EQ(bits(rf, gpio::PortA::afrl, 4 * 1, 4), 1u);     // PA1 AF1 (TIM2_CH2)
  EXPECT_EQ(bits(rf, gpio::ModerC::reg, 2 * 11, 2), 0b01u);  // PC11 ENABLE output
  EXPECT_EQ(bits(rf, gpio::ModerC::reg, 2 * 10, 2), 0b00u);  // PC10 nFAULT input
  EXPECT_EQ(bits(rf, gpio::PortC::pupdr, 2 * 10, 2), 0b01u);  // with pull-up
  EXPECT_EQ(bits(rf, gpio::ModerC::reg, 2 * 6, 2), 0b01u);   // PC6 contact line
  EXPECT_EQ(bits(rf, gpio::ModerA::reg, 2 * 5, 2), 0b01u);   // PA5 LED
  EXPECT_EQ(bits(rf, gpio::PortA::ospeedr, 2 * 8, 2), pins::kPwmSpeed);
  EXPECT_EQ(bits(rf, gpio::ModerA::reg, 2 * 2, 2), 0b10u);  // PA2 LPUART1_TX, AF12
  EXPECT_EQ(bits(rf, gpio::PortA::afrl, 4 * 2, 4), 12u);
  EXPECT_EQ(bits(rf, gpio::PortA::pupdr, 2 * 3, 2), 0b01u);  // PA3 RX pulled up (idle high)
}

TEST(Stm32Pins, AnalogPinsAreAnalogAndCarryTheAdcChannelsPins) {
  const RegisterFile rf = initialised();
  // README §3 analog rows: PB1, PB12 (ADC1), PC0..PC3, PA6, PC4 (ADC2), PA11, PA12 (USB).
  const std::pair<const Register*, std::uint32_t> analog[] = {
      {&gpio::ModerB::reg, 1}, {&gpio::ModerB::reg, 12}, {&gpio::ModerC::reg, 0},
      {&gpio::ModerC::reg, 1}, {&gpio::ModerC::reg, 2},  {&gpio::ModerC::reg, 3},
      {&gpio::ModerA::reg, 6}, {&gpio::ModerC::reg, 4},  {&gpio::ModerA::reg, 11},
      {&gpio::ModerA::reg, 12}};
  for (const auto& [moder, n] : analog) {
    EXPECT_EQ(bits(rf, *moder, 2 * n, 2), 0b11u) << moder->peripheral << " pin " << n;
  }
  std::size_t analog_rows = 0;
  for (const pins::Pin& pin : pins::kPins) {
    analog_rows += pin.mode == Mode::analog ? 1 : 0;
  }
  EXPECT_EQ(analog_rows, std::size(analog));
  // The ADC channels used by adc.hpp are those pins' channels (README §3, facts §4.4).
  EXPECT_EQ(adc::kCurrentChannel, 12u);  // PB1
  EXPECT_EQ(adc::kSupplyChannel, 11u);   // PB12
}

TEST(Stm32Pins, PinsOutsideTheTableKeepTheirResetState) {
  const RegisterFile rf = initialised();
  // SWD PA13/PA14 stay AF (10) with AF0 (AFRH reset 0); PA4, PA7 stay analog (11).
  EXPECT_EQ(bits(rf, gpio::ModerA::reg, 2 * 13, 2), 0b10u);
  EXPECT_EQ(bits(rf, gpio::ModerA::reg, 2 * 14, 2), 0b10u);
  EXPECT_EQ(bits(rf, gpio::PortA::afrh, 4 * 5, 8), 0u);
  EXPECT_EQ(bits(rf, gpio::ModerA::reg, 2 * 4, 2), 0b11u);
  EXPECT_EQ(bits(rf, gpio::ModerA::reg, 2 * 7, 2), 0b11u);
  EXPECT_EQ(bits(rf, gpio::ModerB::reg, 2 * 4, 2), 0b10u);  // PB4 (UCPD / JTAG) untouched
  // AFRL of port A: PA0/PA1 AF1, PA2/PA3 AF12 (the host link), nothing else.
  EXPECT_EQ(rf.peek(gpio::PortA::afrl), 0x0000'CC11u);
  EXPECT_EQ(bits(rf, rcc::Ahb2enr::reg, 0, 3), 0b111u);     // GPIOA/B/C clocks
}

}  // namespace
}  // namespace palp::stm32::pins_test
