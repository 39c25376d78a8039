// SPDX-License-Identifier: Apache-2.0
// The pin table of the STM32G474 board: README §3 ("The pin table"), the binding contract, as ONE
// constexpr table, and the init that configures every pin from it (clocks of GPIOA/B/C, then per
// pin MODER, OTYPER, OSPEEDR, PUPDR and AFRL/AFRH). Pins not in the table (SWD PA13/PA14, the
// BOOT0, the UCPD pins) keep their reset state. GPIO register layout:
// regs/gpio.hpp (SVD offsets, facts §2 bases); AF numbers: README §3 from facts §4.2, §4.3.
#pragma once

#include <array>
#include <cstdint>

#include "regs/gpio.hpp"
#include "regs/rcc.hpp"

namespace palp::stm32::pins {

enum class Port : std::uint8_t { a, b, c };

/// MODER codes (RM0440; the README: "analog means MODER = 11").
enum class Mode : std::uint8_t { input = 0b00, output = 0b01, alternate = 0b10, analog = 0b11 };
/// PUPDR codes (RM0440, not in the facts sheet): 00 none, 01 pull-up, 10 pull-down.
enum class Pull : std::uint8_t { none = 0b00, up = 0b01, down = 0b10 };

struct Pin {
  Port port;
  std::uint8_t number;  // 0..15
  Mode mode;
  std::uint8_t af;  // alternate function number (alternate mode only)
  Pull pull;
  const char* signal;
};

/// OSPEEDR code of the alternate-function pins: 10 = "high" (RM0440; not in the facts sheet —
/// check): the gate-driver inputs want clean edges (on the encoder inputs speed has no effect).
/// All other pins keep the reset speed (low).
inline constexpr std::uint32_t kPwmSpeed = 0b10;

// README §3, row for row (same order). PA15 (TIM2_ETR, encoder index): its AF is "check in the
// datasheet DS12288" in the README, so it is left an input here until that is checked; the index
// is not used by the timers yet. The last two rows are the NUCLEO's own wiring the README leaves
// alone (PA2/PA3 to the ST-LINK virtual COM port) taken as LPUART1 for the host link
// (link_uart.hpp): AF12 is from the G474 datasheet's AF table, not the facts sheet (check DS12288).
inline constexpr std::array<Pin, 23> kPins = {{
    {Port::a, 8, Mode::alternate, 6, Pull::none, "TIM1_CH1 leg A high side"},
    {Port::b, 13, Mode::alternate, 6, Pull::none, "TIM1_CH1N leg A low side"},
    {Port::a, 9, Mode::alternate, 6, Pull::none, "TIM1_CH2 leg B high side"},
    {Port::b, 14, Mode::alternate, 6, Pull::none, "TIM1_CH2N leg B low side"},
    {Port::c, 11, Mode::output, 0, Pull::none, "driver enable (high = on)"},
    {Port::c, 10, Mode::input, 0, Pull::up, "driver fault (low = fault)"},
    {Port::b, 1, Mode::analog, 0, Pull::none, "ADC1_IN12 coil current"},
    {Port::b, 12, Mode::analog, 0, Pull::none, "ADC1_IN11 bridge supply"},
    {Port::a, 0, Mode::alternate, 1, Pull::none, "TIM2_CH1 encoder A"},
    {Port::a, 1, Mode::alternate, 1, Pull::none, "TIM2_CH2 encoder B"},
    {Port::a, 15, Mode::input, 0, Pull::none, "TIM2_ETR encoder index (AF: check DS12288)"},
    {Port::c, 0, Mode::analog, 0, Pull::none, "ADC2_IN6 pressure 1"},
    {Port::c, 1, Mode::analog, 0, Pull::none, "ADC2_IN7 pressure 2"},
    {Port::c, 2, Mode::analog, 0, Pull::none, "ADC2_IN8 pressure 3"},
    {Port::c, 3, Mode::analog, 0, Pull::none, "ADC2_IN9 pressure 4"},
    {Port::a, 6, Mode::analog, 0, Pull::none, "ADC2_IN3 pressure 5"},
    {Port::c, 4, Mode::analog, 0, Pull::none, "ADC2_IN5 pressure 6"},
    {Port::a, 11, Mode::analog, 0, Pull::none, "USB_DM"},
    {Port::a, 12, Mode::analog, 0, Pull::none, "USB_DP"},
    {Port::c, 6, Mode::output, 0, Pull::none, "contact line"},
    {Port::a, 5, Mode::output, 0, Pull::none, "status LED LD2"},
    {Port::a, 2, Mode::alternate, 12, Pull::none, "LPUART1_TX to the ST-LINK VCP"},
    {Port::a, 3, Mode::alternate, 12, Pull::up, "LPUART1_RX from the ST-LINK VCP"},
}};

constexpr const gpio::PortRegs& port_regs(Port port) {
  return port == Port::a ? gpio::kPortA : port == Port::b ? gpio::kPortB : gpio::kPortC;
}

/// True if no (port, pin) appears twice in `pins`.
template <std::size_t N>
constexpr bool no_pin_twice(const std::array<Pin, N>& pins) {
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = i + 1; j < N; ++j) {
      if (pins[i].port == pins[j].port && pins[i].number == pins[j].number) {
        return false;
      }
    }
  }
  return true;
}
static_assert(no_pin_twice(kPins), "README §3: no pin twice");

namespace detail {

template <RegisterAccess A>
void set_bits(A& io, const Register& reg, std::uint32_t position, std::uint32_t width,
              std::uint32_t value) {
  const Field f{"", static_cast<std::uint8_t>(position), static_cast<std::uint8_t>(width)};
  write_field(io, reg, f, value);
}

}  // namespace detail

/// Configures one pin. Outputs come up low (ODR resets to 0): ENABLE low keeps the bridge off.
/// The AF is written before MODER selects it, so the pin never drives a wrong function.
template <RegisterAccess A>
void configure(A& io, const Pin& pin) {
  const gpio::PortRegs& regs = port_regs(pin.port);
  const std::uint32_t n = pin.number;
  detail::set_bits(io, regs.pupdr, 2 * n, 2, static_cast<std::uint32_t>(pin.pull));
  detail::set_bits(io, regs.otyper, n, 1, 0);  // push-pull
  if (pin.mode == Mode::alternate) {
    detail::set_bits(io, regs.ospeedr, 2 * n, 2, kPwmSpeed);
    detail::set_bits(io, n < 8 ? regs.afrl : regs.afrh, 4 * (n % 8), 4, pin.af);
  }
  detail::set_bits(io, regs.moder, 2 * n, 2, static_cast<std::uint32_t>(pin.mode));
}

/// GPIOA/B/C clocks on, then every pin of `pins` (the board: kPins).
template <RegisterAccess A, std::size_t N>
void init(A& io, const std::array<Pin, N>& pins) {
  using rcc::Ahb2enr;
  const std::uint32_t clocks =
      Ahb2enr::GPIOAEN.mask() | Ahb2enr::GPIOBEN.mask() | Ahb2enr::GPIOCEN.mask();
  io.write(Ahb2enr::reg.address(), read(io, Ahb2enr::reg) | clocks);
  (void)read(io, Ahb2enr::reg);  // the bus delay after a clock enable (facts §3.2 step 1)
  for (const Pin& pin : pins) {
    configure(io, pin);
  }
}

/// The target: every pin of the README table.
void init_target();

}  // namespace palp::stm32::pins
