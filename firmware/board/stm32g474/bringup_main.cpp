// SPDX-License-Identifier: Apache-2.0
// palp-stm32-bringup.elf: the first image a lab flashes to see an STM32G474 board alive. The
// reset handler (startup.cpp) has already set the clocks; main() only blinks the status LED
// (PA5, NUCLEO LD2; README pin table): slowly when the clock init succeeded, about four times
// faster when it failed (startup::clock_status()). The period is a busy-wait, not a timer: about
// 1 s per cycle at 170 MHz, not a measurement.
#include <cstdint>

#include "regs/gpio.hpp"
#include "regs/rcc.hpp"
#include "startup.hpp"

namespace {

using namespace palp::stm32;

void wait(std::uint32_t iterations) {
  for (std::uint32_t k = 0; k < iterations; ++k) {
    asm volatile("" ::: "memory");  // keeps the loop: one compare, branch and add per round
  }
}

}  // namespace

int main() {
  Mmio io;
  write_field(io, rcc::Ahb2enr::reg, rcc::Ahb2enr::GPIOAEN, 1);
  (void)read(io, rcc::Ahb2enr::reg);  // the clock enable takes effect before GPIOA is written
  write_field(io, gpio::ModerA::reg, gpio::ModerA::MODER5, gpio::ModerA::kOutput);

  const bool clock_ok = startup::clock_status() == clock::Status::ok;
  const std::uint32_t half_period = clock_ok ? 28'000'000u : 7'000'000u;
  while (true) {
    io.write(gpio::BsrrA::reg.address(), gpio::BsrrA::BS5.encode(1));
    wait(half_period);
    io.write(gpio::BsrrA::reg.address(), gpio::BsrrA::BR5.encode(1));
    wait(half_period);
  }
}
