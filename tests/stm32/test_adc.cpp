// SPDX-License-Identifier: Apache-2.0
// The analog front end (firmware/board/stm32g474/adc.hpp) on a host register file: the injected
// trigger and channels, the conversion times, the pressure scan, the DMA set-up and the power-up
// order are COMPUTED from the register values written (facts §4.4, §4.5 restated here) and
// compared with the README's pin table and the 25 µs tick.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "adc.hpp"
#include "register_file.hpp"

// Its own namespace: the stm32 tests build as one unity file, and test_timers has a Status too.
namespace palp::stm32::adc_test {
namespace {

using adc::Status;
using test::RegisterFile;

constexpr std::uint32_t kBufferAddress = 0x2000'1000;  // a stand-in for the DMA buffer

// The register file plus the ADC's part: CR's rs bits ADEN, ADSTART, JADSTART stay set when 0 is
// written to them (facts §4.4 CR write rule), ADCAL clears itself, ADEN raises ISR.ADRDY, ISR bits
// are write-1-to-clear. Each write is logged with the number of reads before it.
class AdcHardware {
 public:
  struct Event {
    std::uint32_t address;
    std::uint32_t value;
    std::uint64_t reads_before;
  };

  std::uint32_t read(std::uint32_t address) { return rf.read(address); }

  void write(std::uint32_t address, std::uint32_t value) {
    events.push_back({address, value, rf.reads()});
    for (const auto& [cr, isr, hangs_calibration, never_ready] :
         {Adc{adc::Cr::adc1, adc::Isr::adc1, adc1_calibration_hangs, adc1_never_ready},
          Adc{adc::Cr::adc2, adc::Isr::adc2, adc2_calibration_hangs, adc2_never_ready}}) {
      if (address == isr.address()) {
        rf.poke(isr, rf.peek(isr) & ~value);
        return;
      }
      if (address == cr.address()) {
        constexpr std::uint32_t kSticky =
            adc::Cr::ADEN.mask() | adc::Cr::ADSTART.mask() | adc::Cr::JADSTART.mask();
        std::uint32_t word = value | (rf.peek(cr) & kSticky);
        if (!hangs_calibration) {
          word &= ~adc::Cr::ADCAL.mask();
        }
        rf.write(address, word);
        if (adc::Cr::ADEN.decode(value) == 1 && !never_ready) {
          rf.poke(isr, rf.peek(isr) | adc::Isr::ADRDY.mask());
        }
        return;
      }
    }
    rf.write(address, value);
  }

  std::uint32_t field(const Register& reg, const Field& f) const { return f.decode(rf.peek(reg)); }

  /// The values written to `reg`, in order.
  std::vector<Event> writes_to(const Register& reg) const {
    std::vector<Event> out;
    for (const Event& e : events) {
      if (e.address == reg.address()) {
        out.push_back(e);
      }
    }
    return out;
  }

  /// Position of the first write to `reg` in the write log (the log's size if none).
  std::size_t index_of_first_write(const Register& reg) const {
    std::size_t i = 0;
    while (i < events.size() && events[i].address != reg.address()) {
      ++i;
    }
    return i;
  }

  RegisterFile rf;
  std::vector<Event> events;
  bool adc1_calibration_hangs = false;
  bool adc1_never_ready = false;
  bool adc2_calibration_hangs = false;
  bool adc2_never_ready = false;

 private:
  struct Adc {
    const Register& cr;
    const Register& isr;
    bool hangs_calibration;
    bool never_ready;
  };
};

// Conversion time from the registers: f_ADC = HCLK / 4 for CKMODE 11 (facts §4.4 CCR), sample
// cycles from the SMPR code (facts §4.4 table), + 12.5 cycles at 12 bit (RM0440).
double conversion_ns_from(const AdcHardware& hw, std::uint32_t smp_code) {
  EXPECT_EQ(hw.field(adc::Ccr::reg, adc::Ccr::CKMODE), 0b11u);
  constexpr double kSampleCycles[8] = {2.5, 6.5, 12.5, 24.5, 47.5, 92.5, 247.5, 640.5};
  const double f_adc_hz = 170e6 / 4.0;
  return (kSampleCycles[smp_code] + 12.5) / f_adc_hz * 1e9;
}

AdcHardware initialised() {
  AdcHardware hw;
  EXPECT_EQ(adc::init(hw, kBufferAddress), Status::ok);
  return hw;
}

TEST(Stm32Adc, InjectedGroupIsCurrentThenSupplyOnTim1Trgo2Rising) {
  const AdcHardware hw = initialised();
  using adc::Jsqr;
  EXPECT_EQ(hw.field(Jsqr::adc1, Jsqr::JEXTSEL), 8u);  // facts §4.4: 8 = TIM1_TRGO2 on ADC1/2
  EXPECT_EQ(hw.field(Jsqr::adc1, Jsqr::JEXTEN), 0b01u);  // rising edge
  EXPECT_EQ(hw.field(Jsqr::adc1, Jsqr::JL) + 1, 2u);
  EXPECT_EQ(hw.field(Jsqr::adc1, Jsqr::JSQ1), 12u);  // README: PB1 = ADC1_IN12, coil current
  EXPECT_EQ(hw.field(Jsqr::adc1, Jsqr::JSQ2), 11u);  // README: PB12 = ADC1_IN11, supply
  EXPECT_EQ(hw.field(adc::Ier::adc1, adc::Ier::JEOSIE), 1u);
  EXPECT_EQ(hw.field(adc::Cr::adc1, adc::Cr::JADSTART), 1u);  // armed
  EXPECT_EQ(hw.field(adc::Cr::adc1, adc::Cr::ADEN), 1u);
}

TEST(Stm32Adc, InjectedConversionsTake871NsEachAndEndWithin2UsOfTheTrigger) {
  const AdcHardware hw = initialised();
  const double current_ns = conversion_ns_from(hw, hw.field(adc::Smpr2::adc1, adc::Smpr2::SMP12));
  const double supply_ns = conversion_ns_from(hw, hw.field(adc::Smpr2::adc1, adc::Smpr2::SMP11));
  EXPECT_NEAR(current_ns, 870.6, 0.1);  // 37 cycles at 42.5 MHz
  EXPECT_NEAR(supply_ns, 870.6, 0.1);
  EXPECT_LT(current_ns + supply_ns, 2'000.0);  // vs the 25 µs tick at 40 kHz
  EXPECT_NEAR(current_ns, adc::conversion_ns(adc::kInjectedSampleCode), 1e-9);
}

TEST(Stm32Adc, RegularScanIsTheSixPressureChannelsInPaperOrderBySoftwareStart) {
  const AdcHardware hw = initialised();
  using adc::Sqr1;
  using adc::Sqr2;
  EXPECT_EQ(hw.field(Sqr1::adc2, Sqr1::L) + 1, 6u);
  // README pin table: PC0, PC1, PC2, PC3, PA6, PC4 = ADC2_IN6, 7, 8, 9, 3, 5.
  const std::uint32_t sequence[6] = {
      hw.field(Sqr1::adc2, Sqr1::SQ1), hw.field(Sqr1::adc2, Sqr1::SQ2),
      hw.field(Sqr1::adc2, Sqr1::SQ3), hw.field(Sqr1::adc2, Sqr1::SQ4),
      hw.field(Sqr2::adc2, Sqr2::SQ5), hw.field(Sqr2::adc2, Sqr2::SQ6)};
  const std::uint32_t expected[6] = {6, 7, 8, 9, 3, 5};
  double scan_ns = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(sequence[i], expected[i]) << "conversion " << i + 1;
    const Field smp{"SMP", static_cast<std::uint8_t>(3 * sequence[i]), 3};  // SMPR1: ch 0..9
    scan_ns += conversion_ns_from(hw, hw.field(adc::Smpr1::adc2, smp));
  }
  EXPECT_NEAR(scan_ns, 6 * 60 / 42.5e6 * 1e9, 0.1);  // 47.5 + 12.5 cycles each: 8.47 µs
  EXPECT_LT(scan_ns, 25'000.0 / 2);
  EXPECT_EQ(hw.field(adc::Cfgr::adc2, adc::Cfgr::EXTEN), 0u);  // software start from the tick
  EXPECT_EQ(hw.field(adc::Cfgr::adc2, adc::Cfgr::CONT), 0u);   // one scan per start
  EXPECT_EQ(hw.field(adc::Cfgr::adc2, adc::Cfgr::RES), 0u);    // 12 bit
}

TEST(Stm32Adc, DmaCopiesSixHalfwordsFromAdc2DrIntoTheBufferCircularly) {
  const AdcHardware hw = initialised();
  using namespace dma;
  EXPECT_EQ(hw.field(Dmamux0::reg, Dmamux0::DMAREQ_ID), 36u);  // facts §4.5: ADC2
  EXPECT_EQ(hw.rf.peek(Cpar1::reg), 0x5000'0140u);             // ADC2 base + DR 0x40 (facts §4.4)
  EXPECT_EQ(hw.rf.peek(Cmar1::reg), kBufferAddress);
  EXPECT_EQ(hw.field(Cndtr1::reg, Cndtr1::NDT), 6u);
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::CIRC), 1u);
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::DIR), 0u);  // peripheral -> memory
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::MINC), 1u);
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::PINC), 0u);
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::PSIZE), 0b01u);  // 16 bit
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::MSIZE), 0b01u);
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::MEM2MEM), 0u);
  EXPECT_EQ(hw.field(Ccr1::reg, Ccr1::EN), 1u);
  EXPECT_EQ(hw.field(adc::Cfgr::adc2, adc::Cfgr::DMAEN), 1u);
  EXPECT_EQ(hw.field(adc::Cfgr::adc2, adc::Cfgr::DMACFG), 1u);  // circular on the ADC side too
  EXPECT_EQ(hw.field(rcc::Ahb1enr::reg, rcc::Ahb1enr::DMA1EN), 1u);
  EXPECT_EQ(hw.field(rcc::Ahb1enr::reg, rcc::Ahb1enr::DMAMUX1EN), 1u);
  // The request is routed and the channel configured before EN is set.
  const auto ccr_writes = hw.writes_to(Ccr1::reg);
  ASSERT_EQ(ccr_writes.size(), 2u);
  EXPECT_EQ(Ccr1::EN.decode(ccr_writes[0].value), 0u);
  EXPECT_LT(hw.index_of_first_write(Dmamux0::reg), hw.index_of_first_write(Ccr1::reg));
  EXPECT_LT(hw.index_of_first_write(Cmar1::reg), hw.index_of_first_write(Ccr1::reg));
}

// Per ADC: DEEPPWD cleared, ADVREGEN, >= 20 µs of reads, ADCAL, ADEN — and the clock first.
void expect_power_up_order(const AdcHardware& hw, const Register& cr) {
  const auto writes = hw.writes_to(cr);
  ASSERT_GE(writes.size(), 4u);
  EXPECT_EQ(writes[0].value, 0u);  // DEEPPWD = 0 before the regulator
  EXPECT_EQ(writes[1].value, adc::Cr::ADVREGEN.mask());
  EXPECT_EQ(writes[2].value, adc::Cr::ADVREGEN.mask() | adc::Cr::ADCAL.mask());
  EXPECT_EQ(adc::Cr::ADCALDIF.decode(writes[2].value), 0u);  // single-ended
  // 20 µs = 3400 HCLK cycles; one register read is at least one cycle.
  EXPECT_GE(writes[2].reads_before - writes[1].reads_before, 3400u);
  EXPECT_EQ(writes[3].value, adc::Cr::ADVREGEN.mask() | adc::Cr::ADEN.mask());
  EXPECT_GE(writes[3].reads_before - writes[2].reads_before, 16u);  // >= 4 ADC clocks
  const auto ccr = hw.writes_to(adc::Ccr::reg);
  ASSERT_EQ(ccr.size(), 1u);
  EXPECT_LE(ccr[0].reads_before, writes[1].reads_before);  // ADC clock before the regulator
}

TEST(Stm32Adc, PowerUpIsRegulatorWaitCalibrationEnableOnBothAdcs) {
  const AdcHardware hw = initialised();
  expect_power_up_order(hw, adc::Cr::adc1);
  expect_power_up_order(hw, adc::Cr::adc2);
  EXPECT_EQ(hw.field(rcc::Ahb2enr::reg, rcc::Ahb2enr::ADC12EN), 1u);
  // JADSTART is the last CR write of ADC1, and carries no other rs bit.
  const auto writes = hw.writes_to(adc::Cr::adc1);
  EXPECT_EQ(writes.back().value, adc::Cr::ADVREGEN.mask() | adc::Cr::JADSTART.mask());
  EXPECT_EQ(writes.size(), 5u);
}

TEST(Stm32Adc, EachStuckFlagReportsItsOwnStatus) {
  AdcHardware cal1;
  cal1.adc1_calibration_hangs = true;
  EXPECT_EQ(adc::init(cal1, kBufferAddress), Status::adc1_calibration_timeout);
  AdcHardware rdy1;
  rdy1.adc1_never_ready = true;
  EXPECT_EQ(adc::init(rdy1, kBufferAddress), Status::adc1_not_ready);
  AdcHardware cal2;
  cal2.adc2_calibration_hangs = true;
  EXPECT_EQ(adc::init(cal2, kBufferAddress), Status::adc2_calibration_timeout);
  AdcHardware rdy2;
  rdy2.adc2_never_ready = true;
  EXPECT_EQ(adc::init(rdy2, kBufferAddress), Status::adc2_not_ready);
  // A failed power-up arms nothing.
  EXPECT_TRUE(rdy2.writes_to(adc::Jsqr::adc1).empty());
  EXPECT_EQ(rdy2.field(adc::Cr::adc1, adc::Cr::JADSTART), 0u);
}

TEST(Stm32Adc, TickStartsTheScanWithAdstartAloneAndTakesBothInjectedCodes) {
  AdcHardware hw = initialised();
  adc::start_pressure_scan(hw);
  EXPECT_EQ(hw.writes_to(adc::Cr::adc2).back().value,
            adc::Cr::ADVREGEN.mask() | adc::Cr::ADSTART.mask());
  hw.rf.poke(adc::Jdr1::adc1, 3277);  // 3 A (README §5)
  hw.rf.poke(adc::Jdr2::adc1, 1234);
  hw.rf.poke(adc::Isr::adc1, adc::Isr::ADRDY.mask() | adc::Isr::JEOC.mask() |
                                 adc::Isr::JEOS.mask());
  const adc::InjectedCodes codes = adc::take_injected(hw);
  EXPECT_EQ(codes.current, 3277);
  EXPECT_EQ(codes.supply, 1234);
  EXPECT_EQ(hw.rf.peek(adc::Isr::adc1), adc::Isr::ADRDY.mask());  // JEOC, JEOS cleared
}

}  // namespace
}  // namespace palp::stm32::adc_test
