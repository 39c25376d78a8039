// SPDX-License-Identifier: Apache-2.0
// The control-loop timers of the STM32G474 board, written against the register-access seam
// (regs/register.hpp) so tests/stm32 runs them on a host register file:
// - TIM1: centre-aligned complementary PWM on CH1/CH1N (leg A: PA8/PB13) and CH2/CH2N (leg B:
//   PA9/PB14) of the DRV8323's 6x PWM inputs (README §3), one PWM period = one control tick, dead
//   time from nanoseconds, and TRGO2 = OC4REF as the ADC's injected trigger at the counter top.
// - The coil voltage -> CCR1/CCR2 map (bipolar, both legs centred at 50 %).
// - TIM2: quadrature encoder, mode 3 (x4), input filter, 32-bit counter; the core takes its low
//   16 bits.
// - IWDG: a 75 ms nominal timeout from the LSI, started by the key sequence.
// Facts: stm32g474-facts.md §4.2 (TIM1), §4.3 (TIM2), §4.7 (IWDG); the pins are the GPIO code's.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>

#include "clock.hpp"
#include "regs/iwdg.hpp"
#include "regs/rcc.hpp"
#include "regs/tim.hpp"

namespace palp::stm32::timers {

/// TIM1 and TIM2 count at PCLK2 / PCLK1 = SYSCLK = 170 MHz (APB prescalers 1, clock.hpp).
inline constexpr std::uint32_t kTimerClockHz = clock::kSysclkHz;

/// The control rates the board supports: one PWM period per control tick.
inline constexpr std::uint32_t kPwm20kHz = 20'000;
inline constexpr std::uint32_t kPwm40kHz = 40'000;

/// TIM1's dead time: 200 ns (README §2 and §4: a second guard behind the DRV8323's own dead
/// time; DTG 34 at t_DTS = 1 / 170 MHz gives exactly 200 ns, facts §4.2).
inline constexpr std::uint32_t kDeadTimeNs = 200;

/// Where an init stopped.
enum class Status : std::uint8_t {
  ok,
  pwm_rate_unsupported,    ///< f_tim / (2 f_pwm) is not a whole number in 2..65535
  dead_time_out_of_range,  ///< above 1008 t_DTS (5929 ns at 170 MHz), DTG's largest
  watchdog_not_updated,    ///< IWDG_SR kept PVU/RVU set
};

// ---- Dead time (facts §4.2 "Dead-time encoding", CKD = 00 so t_DTS = 1 / f_tim) ----

/// Dead time in t_DTS ticks that DTG encodes (all four ranges).
constexpr std::uint32_t dtg_ticks(std::uint8_t dtg) {
  if ((dtg & 0x80u) == 0) {
    return dtg;                              // 0xx: DTG x 1
  }
  if ((dtg & 0xC0u) == 0x80u) {
    return (64u + (dtg & 0x3Fu)) * 2u;       // 10x: 128..254, step 2
  }
  if ((dtg & 0xE0u) == 0xC0u) {
    return (32u + (dtg & 0x1Fu)) * 8u;       // 110: 256..504, step 8
  }
  return (32u + (dtg & 0x1Fu)) * 16u;        // 111: 512..1008, step 16
}

/// The smallest DTG whose dead time is at least `ticks` (never shorter than asked: the dead
/// time is a shoot-through guard); nothing above 1008 ticks.
constexpr std::optional<std::uint8_t> dtg_for_ticks(std::uint32_t ticks) {
  const auto up = [](std::uint32_t n, std::uint32_t step) { return (n + step - 1) / step; };
  if (ticks <= 127) {
    return static_cast<std::uint8_t>(ticks);
  }
  if (ticks <= 254) {
    return static_cast<std::uint8_t>(0x80u | (up(ticks, 2) - 64u));
  }
  if (ticks <= 504) {
    return static_cast<std::uint8_t>(0xC0u | (up(ticks, 8) - 32u));
  }
  if (ticks <= 1008) {
    return static_cast<std::uint8_t>(0xE0u | (up(ticks, 16) - 32u));
  }
  return std::nullopt;
}

/// DTG for at least `ns` nanoseconds at a t_DTS of 1 / `f_dts_hz` (ticks rounded up).
constexpr std::optional<std::uint8_t> dtg_for_ns(std::uint32_t ns,
                                                 std::uint32_t f_dts_hz = kTimerClockHz) {
  const std::uint64_t ticks =
      (static_cast<std::uint64_t>(ns) * f_dts_hz + 999'999'999u) / 1'000'000'000u;
  return ticks > 1008 ? std::nullopt : dtg_for_ticks(static_cast<std::uint32_t>(ticks));
}

static_assert(dtg_for_ns(kDeadTimeNs) == 34, "README: DTG 34 = 200 ns");

// ---- PWM period ----

/// ARR for centre-aligned counting: the counter runs 0 -> ARR -> 0, so one PWM period is
/// 2 ARR timer clocks (PSC 0): ARR = f_tim / (2 f_pwm) (facts §4.2); nothing if not exact.
constexpr std::optional<std::uint32_t> arr_for_pwm(std::uint32_t pwm_hz,
                                                   std::uint32_t f_tim_hz = kTimerClockHz) {
  if (pwm_hz == 0 || f_tim_hz % (2u * pwm_hz) != 0) {
    return std::nullopt;
  }
  const std::uint32_t arr = f_tim_hz / (2u * pwm_hz);
  return arr >= 2 && arr <= 0xFFFF ? std::optional<std::uint32_t>(arr) : std::nullopt;
}

static_assert(arr_for_pwm(kPwm20kHz) == 4250 && arr_for_pwm(kPwm40kHz) == 2125);

// ---- Coil voltage -> duty ----

struct BridgeDuty {
  std::uint32_t ccr1;  ///< leg A (OUTA, coil +): high side on while CNT < CCR1 (PWM mode 1)
  std::uint32_t ccr2;  ///< leg B (OUTB, coil -)
};

/// The compare values for `v_coil_V` on a bridge fed with `supply_V` (README §2, §4):
/// duty_A = 1/2 + v / (2 supply), duty_B = 1/2 - v / (2 supply). The difference CCR1 - CCR2 =
/// round(v / supply x ARR) is exact (the mean coil voltage is quantised to supply / ARR: 5.6 mV
/// at 20 kHz, 11.3 mV at 40 kHz) and the two are centred on ARR / 2 within half a count, so 0 V
/// is CCR1 = CCR2 also when ARR is odd (40 kHz: 2125 -> 1062/1062).
/// Sign: +v puts leg A above leg B, current OUTA -> coil + -> OUTB, force toward +z.
/// |v| is clamped to the supply (+supply: A 100 %, B 0 %); NaN, or a supply that is not a
/// positive number, gives 0 V (both legs at 50 %: no mean voltage across the coil).
inline BridgeDuty duty_for_voltage(float v_coil_V, float supply_V, std::uint32_t arr) {
  float ratio = 0.0f;  // v / supply in [-1, 1]
  if (!std::isnan(v_coil_V) && supply_V > 0.0f && std::isfinite(supply_V)) {
    ratio = std::fmax(-1.0f, std::fmin(1.0f, v_coil_V / supply_V));
  }
  const auto arr_signed = static_cast<std::int32_t>(arr);
  const auto diff = static_cast<std::int32_t>(std::lround(ratio * static_cast<float>(arr)));
  const std::int32_t ccr1 = (arr_signed + diff) / 2;  // arr + diff >= 0: floor
  return {static_cast<std::uint32_t>(ccr1), static_cast<std::uint32_t>(ccr1 - diff)};
}

/// Writes the bridge duty for `v_coil_V` (preloaded: takes effect at the next update event).
template <RegisterAccess A>
void set_coil_voltage(A& io, float v_coil_V, float supply_V) {
  const BridgeDuty duty =
      duty_for_voltage(v_coil_V, supply_V, read_field(io, tim1::Arr::reg, tim1::Arr::ARR));
  io.write(tim1::Ccr1::reg.address(), duty.ccr1);
  io.write(tim1::Ccr2::reg.address(), duty.ccr2);
}

// ---- TIM1: the bridge PWM and the ADC trigger ----

/// CMS = 01, centre-aligned mode 1. Any of the three counts the same triangle; they differ only
/// in which direction sets the CCx interrupt flags (facts §4.2), and the board uses no CCx
/// interrupt (the tick runs on the ADC's end of conversion), so the plainest one is taken.
inline constexpr std::uint32_t kCmsCentreAligned1 = 0b01;

/// The ADC trigger: CCR4 = ARR - 1 with OC4 in PWM mode 2 makes OC4REF rise one timer clock
/// (5.9 ns) before the counter's top, once per period, and TRGO2 = OC4REF (MMS2 0111) passes
/// that edge to the ADC (JEXTSEL 8, rising; facts §4.2, §4.4). TRGO2 = update would fire at the
/// top AND the bottom (RCR = 0 updates on both, facts §4.2), and at the bottom both high sides
/// conduct instead of both low sides. CH4 has no pin enabled (its pin PA11 is USB's).
constexpr std::uint32_t adc_trigger_ccr4(std::uint32_t arr) { return arr - 1; }

/// TIM1 at `pwm_hz` (20 or 40 kHz), dead time `dead_time_ns`, both legs at 50 % (0 V).
/// Order: clock, counter (stopped), compare channels with preload, CCER, BDTR without MOE, UG
/// (loads the preloads), CEN, and MOE last, so no output is driven before all is set.
/// Idle-safe: OISx = OISxN = 0 (idle low), OSSI = OSSR = 1 (while MOE = 0 or a channel is off
/// the pins are driven to their inactive/idle level rather than released to float).
template <RegisterAccess A>
Status init_bridge_pwm(A& io, std::uint32_t pwm_hz, std::uint32_t dead_time_ns = kDeadTimeNs) {
  const std::optional<std::uint32_t> arr = arr_for_pwm(pwm_hz);
  if (!arr) {
    return Status::pwm_rate_unsupported;
  }
  const std::optional<std::uint8_t> dtg = dtg_for_ns(dead_time_ns);
  if (!dtg) {
    return Status::dead_time_out_of_range;
  }
  using namespace tim1;
  write_field(io, rcc::Apb2enr::reg, rcc::Apb2enr::TIM1EN, 1);
  (void)read(io, rcc::Apb2enr::reg);  // the bus delay after a clock enable (facts §3.2 step 1)

  // Counter stopped; centre-aligned mode 1, ARR preloaded, CKD 0 (t_DTS = t_CK_INT).
  io.write(Cr1::reg.address(), Cr1::CMS.encode(kCmsCentreAligned1) | Cr1::ARPE.mask());
  io.write(Psc::reg.address(), 0);
  io.write(Arr::reg.address(), *arr);
  io.write(Rcr::reg.address(), 0);

  // CH1, CH2: PWM mode 1 (high side on while CNT < CCRx), preloaded. CH4: PWM mode 2 trigger.
  io.write(Ccmr1::reg.address(), Ccmr1::OC1M.encode(kOcPwm1) | Ccmr1::OC1M_3.encode(kOcPwm1 >> 3) |
                                     Ccmr1::OC1PE.mask() | Ccmr1::OC2M.encode(kOcPwm1) |
                                     Ccmr1::OC2M_3.encode(kOcPwm1 >> 3) | Ccmr1::OC2PE.mask());
  io.write(Ccmr2::reg.address(), Ccmr2::OC4M.encode(kOcPwm2) |
                                     Ccmr2::OC4M_3.encode(kOcPwm2 >> 3) | Ccmr2::OC4PE.mask());
  const BridgeDuty zero = duty_for_voltage(0.0f, 1.0f, *arr);
  io.write(Ccr1::reg.address(), zero.ccr1);
  io.write(Ccr2::reg.address(), zero.ccr2);
  io.write(Ccr4::reg.address(), adc_trigger_ccr4(*arr));

  // TRGO2 = OC4REF; idle states (OISx, OISxN) 0 = low.
  io.write(Cr2::reg.address(), Cr2::MMS2.encode(Cr2::kMms2Oc4Ref));
  // CH1/CH1N, CH2/CH2N enabled, active high (the DRV8323's INHx/INLx are active high).
  io.write(Ccer::reg.address(), Ccer::CC1E.mask() | Ccer::CC1NE.mask() | Ccer::CC2E.mask() |
                                    Ccer::CC2NE.mask());
  // BDTR in one write (LOCK may freeze it, facts §4.2): dead time, OSSI/OSSR, MOE still 0.
  const std::uint32_t bdtr =
      Bdtr::DTG.encode(*dtg) | Bdtr::OSSI.mask() | Bdtr::OSSR.mask() | Bdtr::LOCK.encode(0);
  io.write(Bdtr::reg.address(), bdtr);

  io.write(Egr::reg.address(), Egr::UG.mask());  // load PSC, ARR, CCRx from their preloads
  write_field(io, Cr1::reg, Cr1::CEN, 1);
  io.write(Bdtr::reg.address(), bdtr | Bdtr::MOE.mask());  // outputs on: last
  return Status::ok;
}

// ---- TIM2: the quadrature encoder ----

/// Input filter IC1F = IC2F = 0101: sampled at f_DTS / 2 = 85 MHz, N = 8 (facts §4.3 table), a
/// level must hold 8 / 85 MHz = 94.1 ns to pass. At 5 m/s and 1 um per count the counts come
/// at 5 MHz, 200 ns apart (A and B each toggle every 400 ns); the filter window is at most half
/// the 200 ns (margin for the encoder's A/B phase error), i.e. it passes count rates up to
/// 1 / (2 x 94.1 ns) = 5.31 MHz. The next code (0110, 141 ns) would not.
inline constexpr std::uint32_t kEncoderFilter = 0b0101;
inline constexpr std::uint32_t kEncoderMaxCountHz = 5'000'000;  // 5 m/s at 1 um per count

/// TIM2 as a x4 quadrature counter on TI1 = A (PA0), TI2 = B (PA1), 32 bits, no polarity
/// inversion (README §9 step 5: invert CC1P if z runs backwards). The index (ETR on PA15) is
/// not set up: its pin's AF is not in the facts sheet (§4.3).
template <RegisterAccess A>
void init_encoder(A& io) {
  using namespace tim2;
  write_field(io, rcc::Apb1enr1::reg, rcc::Apb1enr1::TIM2EN, 1);
  (void)read(io, rcc::Apb1enr1::reg);
  io.write(Cr1::reg.address(), 0);
  io.write(Ccmr1::reg.address(), Ccmr1::CC1S.encode(Ccmr1::kCcInputOwnTi) |
                                     Ccmr1::IC1F.encode(kEncoderFilter) |
                                     Ccmr1::CC2S.encode(Ccmr1::kCcInputOwnTi) |
                                     Ccmr1::IC2F.encode(kEncoderFilter));
  io.write(Ccer::reg.address(), 0);
  io.write(Smcr::reg.address(), Smcr::SMS.encode(Smcr::kEncoderMode3) |
                                    Smcr::SMS_3.encode(Smcr::kEncoderMode3 >> 3));
  io.write(Arr::reg.address(), 0xFFFF'FFFFu);
  io.write(Egr::reg.address(), Egr::UG.mask());
  io.write(Cr1::reg.address(), Cr1::CEN.mask());
}

/// The core's `TickInputs::encoder_timer`: the low 16 bits of the 32-bit count. The counter wraps
/// modulo 2^32 (ARR = 0xFFFF_FFFF) and 2^16 divides 2^32, so the low half wraps modulo 2^16
/// exactly like a 16-bit timer would, which is what the core's Encoder unwraps.
template <RegisterAccess A>
std::uint16_t encoder_count16(A& io) {
  return static_cast<std::uint16_t>(read(io, tim2::Cnt::reg) & 0xFFFFu);
}

// ---- IWDG ----

/// Timeout = (RL + 1) x 4 x 2^PR / f_LSI: PR 0 (/4), RL 599 -> 2400 LSI clocks = 75 ms at the
/// nominal 32 kHz (facts §4.7). The LSI's tolerance is NOT in the facts sheet: with an assumed
/// band of 28.8..35.2 kHz (+-10 %, wider than we expect DS12288 to give: check it) the timeout is
/// 68.2..83.3 ms, inside the 50..100 ms asked of it.
inline constexpr std::uint32_t kIwdgPrescalerCode = 0;  // /4
inline constexpr std::uint32_t kIwdgReload = 599;
inline constexpr std::uint32_t kLsiNominalHz = 32'000;
inline constexpr std::uint32_t kLsiAssumedMinHz = 28'800;
inline constexpr std::uint32_t kLsiAssumedMaxHz = 35'200;

/// Starts the watchdog (it cannot be stopped again, facts §4.7): start, unlock, PR, RLR, wait
/// for SR = 0 (bounded), reload.
template <RegisterAccess A>
Status start_watchdog(A& io) {
  using namespace iwdg;
  io.write(Kr::reg.address(), Kr::kStart);
  io.write(Kr::reg.address(), Kr::kUnlock);
  io.write(Pr::reg.address(), Pr::PR.encode(kIwdgPrescalerCode));
  io.write(Rlr::reg.address(), Rlr::RL.encode(kIwdgReload));
  bool updated = false;
  for (std::uint32_t i = 0; i < clock::kPollLimit && !updated; ++i) {
    updated = read(io, Sr::reg) == 0;
  }
  io.write(Kr::reg.address(), Kr::kReload);
  return updated ? Status::ok : Status::watchdog_not_updated;
}

/// The refresh the control loop calls every tick.
template <RegisterAccess A>
void refresh_watchdog(A& io) {
  io.write(iwdg::Kr::reg.address(), iwdg::Kr::kReload);
}

/// The target's instantiations (timers.cpp), as clock::init_target().
Status init_bridge_pwm_target(std::uint32_t pwm_hz);
void init_encoder_target();
Status start_watchdog_target();

}  // namespace palp::stm32::timers
