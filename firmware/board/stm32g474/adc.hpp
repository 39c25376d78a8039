// SPDX-License-Identifier: Apache-2.0
// The analog front end of the STM32G474 board (README §2, §3, §5): ADC1's injected group takes
// the coil current (PB1, ADC1_IN12) and then the bridge supply (PB12, ADC1_IN11) on TIM1 TRGO2, the
// instant one timer clock before the PWM counter's top (timers.hpp); its end-of-sequence
// interrupt (ADC1_2, IRQ 18; facts §2) runs the control tick. ADC2 scans the six pressure
// channels as a regular sequence that the tick starts by software, and DMA1 channel 1 (DMAMUX1
// request ADC2 = 36) copies the six codes into a fixed buffer, circularly. Written against the
// register seam (regs/register.hpp) so tests/stm32 computes the result from the registers.
// Registers and sequences: stm32g474-facts.md §4.4 (ADC), §4.5 (DMA, DMAMUX).
#pragma once

#include <array>
#include <cstdint>

#include "clock.hpp"
#include "regs/adc.hpp"
#include "regs/dma.hpp"
#include "regs/rcc.hpp"

namespace palp::stm32::adc {

// The ADC clock: synchronous HCLK/4 (CCR.CKMODE = 11; facts §4.4 step 1) = 42.5 MHz, below both
// limits the facts sheet quotes (60 and 75 MHz) and needing no RCC kernel-clock selection.
inline constexpr std::uint32_t kHclkDivider = 4;
inline constexpr std::uint32_t kAdcClockHz = clock::kSysclkHz / kHclkDivider;

// Channels: README §3 pin table (binding).
inline constexpr std::uint32_t kCurrentChannel = 12;  // PB1 = ADC1_IN12, INA240 output
inline constexpr std::uint32_t kSupplyChannel = 11;   // PB12 = ADC1_IN11, 24 V divider
/// Pressure channels 1..6 in paper order: PC0, PC1, PC2, PC3, PA6, PC4 = ADC2_IN6, 7, 8, 9, 3, 5.
inline constexpr std::array<std::uint32_t, 6> kPressureChannels = {6, 7, 8, 9, 3, 5};

// Sample times (facts §4.4 SMPR codes). Current and supply: 24.5 cycles (README §5: ≥ 24.5 at
// 42.5 MHz; the 1 nF / 10 nF at the pins supply the sampling charge). Pressure: 47.5 cycles, for
// the dividers' ~6.6 kΩ source with 10 nF at the pin.
inline constexpr std::uint32_t kInjectedSampleCode = SampleTime::k24_5Cycles;
inline constexpr std::uint32_t kPressureSampleCode = SampleTime::k47_5Cycles;
/// The 12-bit successive approximation: 12.5 ADC cycles per conversion after sampling (RM0440's
/// t_CONV = t_SMPL + t_SAR; not in the facts sheet — check in RM0440/DS12288).
inline constexpr std::uint32_t kSarHalfCycles12Bit = 25;

/// One conversion's time in ns for a sample-time code: (sample + 12.5) ADC cycles.
constexpr double conversion_ns(std::uint32_t sample_code) {
  return (SampleTime::kHalfCycles[sample_code] + kSarHalfCycles12Bit) / 2.0 * 1e9 / kAdcClockHz;
}
// 24.5 + 12.5 = 37 cycles = 870.6 ns per injected conversion, 1.74 µs for current + supply;
// 47.5 + 12.5 = 60 cycles = 1.41 µs per pressure channel, 8.47 µs for six: both end well within
// the 25 µs tick of 40 kHz PWM.
static_assert(2 * conversion_ns(kInjectedSampleCode) < 2'000.0);
static_assert(6 * conversion_ns(kPressureSampleCode) < 10'000.0);

// t_ADCVREG_STUP = 20 µs (facts §4.4 step 2) = 3400 HCLK cycles at 170 MHz; each read of an ADC
// register takes at least one AHB cycle, so 4000 reads of CR are > 20 µs.
inline constexpr std::uint32_t kRegulatorWaitReads = 4000;
// ≥ 4 ADC clocks (16 HCLK cycles) between the end of calibration and ADEN (facts §4.4 step 4).
inline constexpr std::uint32_t kCalibrationToEnableReads = 32;
// CR bits that are written 1 only ("rs"; facts §4.4 CR write rule): ADEN, ADDIS, ADSTART,
// JADSTART, ADSTP, JADSTP (bits 0..5) and ADCAL (31). A CR write carries 0 in all of them but the
// one meant.
inline constexpr std::uint32_t kCrRsBits = 0x3Fu | Cr::ADCAL.mask();

inline constexpr std::uint32_t kPressureCount = kPressureChannels.size();

/// Where init stopped (each polled flag its own value, as in clock.hpp).
enum class Status : std::uint8_t {
  ok,
  adc1_calibration_timeout,  ///< ADC1 CR.ADCAL never cleared
  adc1_not_ready,            ///< ADC1 ISR.ADRDY never rose after ADEN
  adc2_calibration_timeout,
  adc2_not_ready,
};

/// The two codes of one injected sequence (JDR1, JDR2 in JSQ order).
struct InjectedCodes {
  std::uint16_t current;
  std::uint16_t supply;
};

namespace detail {

/// Sets one rs bit of CR (or ADVREGEN) with every other rs bit written 0 (facts §4.4).
template <RegisterAccess A>
void cr_command(A& io, const Register& cr, std::uint32_t bits) {
  io.write(cr.address(), (read(io, cr) & ~kCrRsBits) | bits);
}

/// Regulator on, its start-up wait, single-ended calibration, enable (facts §4.4 steps 2..5).
template <RegisterAccess A>
bool power_up(A& io, const Register& cr, const Register& isr, Status& failure,
              Status calibration_timeout, Status not_ready) {
  io.write(cr.address(), 0);  // DEEPPWD = 0 (it is 1 after reset), nothing else
  io.write(cr.address(), Cr::ADVREGEN.mask());
  for (std::uint32_t i = 0; i < kRegulatorWaitReads; ++i) {
    (void)read(io, cr);
  }
  cr_command(io, cr, Cr::ADCAL.mask());  // ADCALDIF = 0: single-ended inputs
  if (!clock::detail::poll(io, cr, Cr::ADCAL, 0)) {
    failure = calibration_timeout;
    return false;
  }
  for (std::uint32_t i = 0; i < kCalibrationToEnableReads; ++i) {
    (void)read(io, cr);
  }
  io.write(isr.address(), Isr::ADRDY.mask());  // clear a stale ADRDY (write 1)
  cr_command(io, cr, Cr::ADEN.mask());
  if (!clock::detail::poll(io, isr, Isr::ADRDY, 1)) {
    failure = not_ready;
    return false;
  }
  return true;
}

}  // namespace detail

/// Clocks, both ADCs powered, calibrated and enabled, ADC1's injected group armed on TIM1 TRGO2
/// with its end-of-sequence interrupt enabled (the NVIC enable of IRQ 18 is the caller's), ADC2's
/// regular scan with circular DMA into the 6 halfwords at `pressure_buffer_address`.
template <RegisterAccess A>
Status init(A& io, std::uint32_t pressure_buffer_address) {
  write_field(io, rcc::Ahb2enr::reg, rcc::Ahb2enr::ADC12EN, 1);
  const std::uint32_t dma_clocks = rcc::Ahb1enr::DMA1EN.mask() | rcc::Ahb1enr::DMAMUX1EN.mask();
  io.write(rcc::Ahb1enr::reg.address(), read(io, rcc::Ahb1enr::reg) | dma_clocks);
  (void)read(io, rcc::Ahb1enr::reg);  // the bus delay after a clock enable (facts §3.2 step 1)
  // The clock mode is set while both ADCs are disabled (facts §4.4 step 1).
  write_field(io, Ccr::reg, Ccr::CKMODE, Ccr::kCkmodeHclkDiv4);

  Status failure = Status::ok;
  if (!detail::power_up(io, Cr::adc1, Isr::adc1, failure, Status::adc1_calibration_timeout,
                        Status::adc1_not_ready) ||
      !detail::power_up(io, Cr::adc2, Isr::adc2, failure, Status::adc2_calibration_timeout,
                        Status::adc2_not_ready)) {
    return failure;
  }

  // ADC1 injected: current then supply, TIM1 TRGO2 rising (facts §4.4 JSQR, JEXTSEL table).
  io.write(Smpr2::adc1.address(), (read(io, Smpr2::adc1) & ~(Smpr2::SMP11.mask() |
                                                             Smpr2::SMP12.mask())) |
                                      Smpr2::SMP11.encode(kInjectedSampleCode) |
                                      Smpr2::SMP12.encode(kInjectedSampleCode));
  io.write(Jsqr::adc1.address(),
           Jsqr::JL.encode(2 - 1) | Jsqr::JEXTSEL.encode(Jsqr::kJextselTim1Trgo2) |
               Jsqr::JEXTEN.encode(Jsqr::kJextenRising) | Jsqr::JSQ1.encode(kCurrentChannel) |
               Jsqr::JSQ2.encode(kSupplyChannel));
  // End of the injected SEQUENCE, not of each conversion: the tick needs both codes.
  write_field(io, Ier::adc1, Ier::JEOSIE, 1);

  // DMA1 channel 1 <- DMAMUX1 channel 0 <- request ADC2 (facts §4.5): request before the channel.
  using namespace dma;
  io.write(Dmamux0::reg.address(), Dmamux0::DMAREQ_ID.encode(Dmamux0::kRequestAdc2));
  io.write(Cpar1::reg.address(), Dr::adc2.address());
  io.write(Cmar1::reg.address(), pressure_buffer_address);
  io.write(Cndtr1::reg.address(), Cndtr1::NDT.encode(kPressureCount));
  const std::uint32_t ccr = Ccr1::CIRC.mask() | Ccr1::MINC.mask() |
                            Ccr1::PSIZE.encode(Ccr1::kSize16Bit) |
                            Ccr1::MSIZE.encode(Ccr1::kSize16Bit);  // DIR 0: ADC -> memory
  io.write(Ccr1::reg.address(), ccr);
  io.write(Ccr1::reg.address(), ccr | Ccr1::EN.mask());

  // ADC2 regular: the six pressure channels, software start (EXTEN 00), one scan per ADSTART.
  std::uint32_t smpr1 = read(io, Smpr1::adc2);
  for (const Field& f : Smpr1::fields) {
    smpr1 = (smpr1 & ~f.mask()) | f.encode(kPressureSampleCode);
  }
  io.write(Smpr1::adc2.address(), smpr1);
  io.write(Sqr1::adc2.address(),
           Sqr1::L.encode(kPressureCount - 1) | Sqr1::SQ1.encode(kPressureChannels[0]) |
               Sqr1::SQ2.encode(kPressureChannels[1]) | Sqr1::SQ3.encode(kPressureChannels[2]) |
               Sqr1::SQ4.encode(kPressureChannels[3]));
  io.write(Sqr2::adc2.address(),
           Sqr2::SQ5.encode(kPressureChannels[4]) | Sqr2::SQ6.encode(kPressureChannels[5]));
  const std::uint32_t cfgr_mask = Cfgr::DMAEN.mask() | Cfgr::DMACFG.mask() | Cfgr::RES.mask() |
                                  Cfgr::EXTEN.mask() | Cfgr::CONT.mask();
  io.write(Cfgr::adc2.address(),
           (read(io, Cfgr::adc2) & ~cfgr_mask) | Cfgr::DMAEN.mask() | Cfgr::DMACFG.mask());

  // Arm the injected trigger last: from here each TRGO2 edge converts.
  detail::cr_command(io, Cr::adc1, Cr::JADSTART.mask());
  return Status::ok;
}

/// From the tick (the ADC1_2 interrupt): start the next pressure scan. It ends 8.5 µs later, so
/// the buffer holds a complete scan, started one tick earlier, when the next tick reads it.
template <RegisterAccess A>
void start_pressure_scan(A& io) {
  detail::cr_command(io, Cr::adc2, Cr::ADSTART.mask());
}

/// From the tick: the injected codes, and the JEOC/JEOS flags cleared so the interrupt ends.
template <RegisterAccess A>
InjectedCodes take_injected(A& io) {
  const InjectedCodes codes{
      static_cast<std::uint16_t>(read_field(io, Jdr1::adc1, Jdr1::JDATA1)),
      static_cast<std::uint16_t>(read_field(io, Jdr2::adc1, Jdr2::JDATA2))};
  io.write(Isr::adc1.address(), Isr::JEOC.mask() | Isr::JEOS.mask());
  return codes;
}

/// The target: init on the memory-mapped registers with the board's own pressure buffer.
Status init_target();
void start_pressure_scan_target();
InjectedCodes take_injected_target();
/// The six pressure codes the DMA writes (paper channel order), the last complete scan.
const volatile std::uint16_t* pressure_codes_target();

}  // namespace palp::stm32::adc
