// SPDX-License-Identifier: Apache-2.0
// Clock init of the STM32G474 board: SYSCLK 170 MHz from HSI16 through the PLL in Range-1 boost
// mode, and a 48 MHz USB clock from HSI48 trimmed by the CRS to the host's SOF (no crystal).
// Written against the register-access seam (regs/register.hpp), so tests/stm32 runs it on a host
// register file and computes the resulting clocks from the values written.
// Recipe and order: stm32g474-facts.md §3.2 (PLL values, wait states, boost, AHB /2 step) and
// §3.3 (HSI48 + CRS).
#pragma once

#include <cstdint>

#include "regs/crs.hpp"
#include "regs/flash.hpp"
#include "regs/pwr.hpp"
#include "regs/rcc.hpp"

namespace palp::stm32::clock {

// What the board promises (facts §3.2, §3.3).
inline constexpr std::uint32_t kHsi16Hz = 16'000'000;
inline constexpr std::uint32_t kSysclkHz = 170'000'000;
inline constexpr std::uint32_t kUsbClockHz = 48'000'000;
// HSI16 / M * N / R = 16 MHz / 4 * 85 / 2 = 170 MHz; VCO input 4 MHz, VCO 340 MHz (facts §3.2).
inline constexpr std::uint32_t kPllM = 4;
inline constexpr std::uint32_t kPllN = 85;
inline constexpr std::uint32_t kPllR = 2;
// 4 wait states: <= 170 MHz in Range-1 boost (facts §3.2 wait-state table).
inline constexpr std::uint32_t kFlashLatency = 4;
// Reads of RCC_CFGR at AHB /2 (85 MHz) before going to /1: each read is at least one AHB cycle,
// so 128 reads are > 1 us, the dwell facts §3.2 (step 5) records.
inline constexpr std::uint32_t kAhbDiv2DwellReads = 128;
// How often a ready flag is polled before init gives up (the flags come within microseconds).
inline constexpr std::uint32_t kPollLimit = 1'000'000;

static_assert(kHsi16Hz / kPllM * kPllN / kPllR == kSysclkHz);
static_assert(kPllR == 2, "PLLR is programmed as 00 (/2) below");

/// Where init stopped: every flag it polls has its own value, so a hung board says which.
enum class Status : std::uint8_t {
  ok,
  flash_latency_not_taken,  ///< FLASH_ACR.LATENCY did not read back 4
  pll_not_ready,            ///< RCC_CR.PLLRDY stayed 0
  sysclk_not_switched,      ///< RCC_CFGR.SWS did not report the PLL
  hsi48_not_ready,          ///< RCC_CRRCR.HSI48RDY stayed 0
};

namespace detail {
template <RegisterAccess A>
bool poll(A& io, const Register& reg, const Field& field, std::uint32_t expected) {
  for (std::uint32_t i = 0; i < kPollLimit; ++i) {
    if (read_field(io, reg, field) == expected) {
      return true;
    }
  }
  return false;
}
}  // namespace detail

/// SYSCLK = HCLK = PCLK1 = PCLK2 = 170 MHz from HSI16 (HSI16 runs after reset). Order (facts
/// §3.2): PWR clock, boost, flash wait states, PLL, AHB /2, switch, AHB /1.
template <RegisterAccess A>
Status init_sysclk_170mhz(A& io) {
  using namespace rcc;
  write_field(io, Apb1enr1::reg, Apb1enr1::PWREN, 1);
  (void)read(io, Apb1enr1::reg);  // the bus delay after a clock enable (facts §3.2 step 1)
  // VOS is Range 1 at reset: boost is R1MODE = 0 (facts §3.2 step 2).
  write_field(io, pwr::Cr5::reg, pwr::Cr5::R1MODE, 0);

  // Wait states and prefetch/caches before the clock rises (facts §3.2 step 3).
  using flash::Acr;
  const std::uint32_t acr_on = Acr::PRFTEN.mask() | Acr::ICEN.mask() | Acr::DCEN.mask();
  io.write(Acr::reg.address(), (read(io, Acr::reg) & ~(Acr::LATENCY.mask() | acr_on)) |
                                   Acr::LATENCY.encode(kFlashLatency) | acr_on);
  if (!detail::poll(io, Acr::reg, Acr::LATENCY, kFlashLatency)) {
    return Status::flash_latency_not_taken;
  }

  // The PLL is off after reset; PLLCFGR is written whole (P and Q outputs off).
  io.write(Pllcfgr::reg.address(), Pllcfgr::PLLSRC.encode(Pllcfgr::kSrcHsi16) |
                                       Pllcfgr::PLLM.encode(kPllM - 1) |
                                       Pllcfgr::PLLN.encode(kPllN) | Pllcfgr::PLLR.encode(0));
  write_field(io, Cr::reg, Cr::PLLON, 1);
  if (!detail::poll(io, Cr::reg, Cr::PLLRDY, 1)) {
    return Status::pll_not_ready;
  }
  write_field(io, Pllcfgr::reg, Pllcfgr::PLLREN, 1);

  // Above 80 MHz: switch at AHB /2, dwell, then /1 (facts §3.2 step 5).
  write_field(io, Cfgr::reg, Cfgr::HPRE, Cfgr::kHpreDiv2);
  write_field(io, Cfgr::reg, Cfgr::SW, Cfgr::kSwPll);
  if (!detail::poll(io, Cfgr::reg, Cfgr::SWS, Cfgr::kSwPll)) {
    return Status::sysclk_not_switched;
  }
  for (std::uint32_t i = 0; i < kAhbDiv2DwellReads; ++i) {
    (void)read(io, Cfgr::reg);
  }
  write_field(io, Cfgr::reg, Cfgr::HPRE, Cfgr::kHpreDiv1);
  return Status::ok;
}

/// The 48 MHz USB clock: HSI48 on, selected for USB (CLK48SEL), CRS trimming it to USB SOF
/// (facts §3.3). The CFGR values equal the reset values; they are written so the board does not
/// depend on what ran before it.
template <RegisterAccess A>
Status init_usb_clock_48mhz(A& io) {
  using namespace rcc;
  write_field(io, Crrcr::reg, Crrcr::HSI48ON, 1);
  if (!detail::poll(io, Crrcr::reg, Crrcr::HSI48RDY, 1)) {
    return Status::hsi48_not_ready;
  }
  write_field(io, Ccipr::reg, Ccipr::CLK48SEL, Ccipr::kClk48Hsi48);
  write_field(io, Apb1enr1::reg, Apb1enr1::CRSEN, 1);
  (void)read(io, Apb1enr1::reg);

  using crs::Cfgr;
  const std::uint32_t cfgr_mask =
      Cfgr::RELOAD.mask() | Cfgr::FELIM.mask() | Cfgr::SYNCDIV.mask() | Cfgr::SYNCSRC.mask();
  io.write(Cfgr::reg.address(),
           (read(io, Cfgr::reg) & ~cfgr_mask) | Cfgr::RELOAD.encode(Cfgr::kReloadUsbSof) |
               Cfgr::FELIM.encode(Cfgr::kFelimDefault) | Cfgr::SYNCDIV.encode(0) |
               Cfgr::SYNCSRC.encode(Cfgr::kSyncSrcUsbSof));
  const std::uint32_t cr = read(io, crs::Cr::reg);
  io.write(crs::Cr::reg.address(), cr | crs::Cr::AUTOTRIMEN.mask() | crs::Cr::CEN.mask());
  return Status::ok;
}

/// Both, in the order the board boots: SYSCLK first, then the USB clock.
template <RegisterAccess A>
Status init(A& io) {
  const Status sysclk = init_sysclk_170mhz(io);
  if (sysclk != Status::ok) {
    return sysclk;
  }
  return init_usb_clock_48mhz(io);
}

/// init() on the target's registers (clock.cpp: the one instantiation with Mmio).
Status init_target();

}  // namespace palp::stm32::clock
