// SPDX-License-Identifier: Apache-2.0
// The control-loop timers (firmware/board/stm32g474/timers.hpp) run on a host register file: the
// PWM frequency, dead time, ADC trigger instant, encoder filter window and watchdog timeout are
// COMPUTED from the register values written (with the facts sheet's formulas and tables, §4.2,
// §4.3, §4.7, restated here independently of the code) and compared with what the board needs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "register_file.hpp"
#include "timers.hpp"

namespace palp::stm32 {
namespace {

using test::RegisterFile;
using timers::Status;

constexpr double kFtimHz = 170e6;

std::uint32_t field(const RegisterFile& rf, const Register& reg, const Field& f) {
  return f.decode(rf.peek(reg));
}

// PWM frequency from the registers: f_tim / ((PSC + 1) x ARR x 2) centre-aligned, x 1 edge.
double pwm_hz_from_registers(const RegisterFile& rf) {
  const double psc = field(rf, tim1::Psc::reg, tim1::Psc::PSC);
  const double arr = field(rf, tim1::Arr::reg, tim1::Arr::ARR);
  const bool centre = field(rf, tim1::Cr1::reg, tim1::Cr1::CMS) != 0;
  return kFtimHz / ((psc + 1.0) * arr * (centre ? 2.0 : 1.0));
}

// Dead time from DTG, decoded with the facts-sheet table (§4.2), CKD from CR1.
double dead_time_ns_from_dtg(std::uint32_t dtg, std::uint32_t ckd) {
  double ticks = 0;
  if ((dtg >> 7) == 0) {
    ticks = dtg;
  } else if ((dtg >> 6) == 0b10) {
    ticks = (64 + (dtg & 0x3F)) * 2.0;
  } else if ((dtg >> 5) == 0b110) {
    ticks = (32 + (dtg & 0x1F)) * 8.0;
  } else {
    ticks = (32 + (dtg & 0x1F)) * 16.0;
  }
  return ticks * (1u << ckd) * 1e9 / kFtimHz;
}

TEST(Stm32Timers, PwmFrequencyComputedFromTheRegistersIs20kHzAnd40kHz) {
  for (const std::uint32_t hz : {timers::kPwm20kHz, timers::kPwm40kHz}) {
    RegisterFile rf;
    ASSERT_EQ(timers::init_bridge_pwm(rf, hz), Status::ok);
    EXPECT_DOUBLE_EQ(pwm_hz_from_registers(rf), hz);
    EXPECT_EQ(field(rf, tim1::Cr1::reg, tim1::Cr1::CMS), 1u);  // centre-aligned mode 1
    EXPECT_EQ(field(rf, tim1::Cr1::reg, tim1::Cr1::ARPE), 1u);
    EXPECT_EQ(field(rf, tim1::Cr1::reg, tim1::Cr1::CEN), 1u);
    EXPECT_EQ(field(rf, rcc::Apb2enr::reg, rcc::Apb2enr::TIM1EN), 1u);
  }
  RegisterFile rf;
  ASSERT_EQ(timers::init_bridge_pwm(rf, timers::kPwm20kHz), Status::ok);
  EXPECT_EQ(field(rf, tim1::Arr::reg, tim1::Arr::ARR), 4250u);  // README §2
}

TEST(Stm32Timers, UnreachablePwmRateIsRefusedBeforeAnyWrite) {
  for (const std::uint32_t hz : {0u, 30'000u, 1'000u}) {  // 2833.3; ARR 85000 > 16 bits
    RegisterFile rf;
    EXPECT_EQ(timers::init_bridge_pwm(rf, hz), Status::pwm_rate_unsupported) << hz;
    EXPECT_TRUE(rf.log().empty()) << hz;
  }
  RegisterFile rf;
  EXPECT_EQ(timers::init_bridge_pwm(rf, timers::kPwm20kHz, 5930), Status::dead_time_out_of_range);
  EXPECT_TRUE(rf.log().empty());
}

TEST(Stm32Timers, DeadTimeDecodedFromBdtrIs200Ns) {
  RegisterFile rf;
  ASSERT_EQ(timers::init_bridge_pwm(rf, timers::kPwm40kHz), Status::ok);
  const std::uint32_t dtg = field(rf, tim1::Bdtr::reg, tim1::Bdtr::DTG);
  EXPECT_EQ(dtg, 34u);
  EXPECT_NEAR(dead_time_ns_from_dtg(dtg, field(rf, tim1::Cr1::reg, tim1::Cr1::CKD)), 200.0, 1e-9);
}

TEST(Stm32Timers, DtgDecodesAllFourRangesAtTheirEnds) {
  struct Case {
    std::uint8_t dtg;
    std::uint32_t ticks;
  };
  for (const Case c : {Case{0x00, 0}, Case{0x22, 34}, Case{0x7F, 127}, Case{0x80, 128},
                       Case{0xBF, 254}, Case{0xC0, 256}, Case{0xDF, 504}, Case{0xE0, 512},
                       Case{0xFF, 1008}}) {
    EXPECT_EQ(timers::dtg_ticks(c.dtg), c.ticks) << int{c.dtg};
    EXPECT_NEAR(dead_time_ns_from_dtg(c.dtg, 0), c.ticks * 1e9 / kFtimHz, 1e-9);
  }
}

// Quantisation: the encoder rounds UP to the next representable dead time, so the decoded value
// is >= the request and less than one step above it: 1 t_DTS (5.88 ns) up to 127 ticks, 2 (11.8
// ns) up to 254, 8 (47.1 ns) up to 504, 16 (94.1 ns) up to 1008 (5929 ns); above: refused.
TEST(Stm32Timers, DeadTimeRoundTripNeverShorterAndWithinOneStep) {
  for (const std::uint32_t ns : {0u, 1u, 5u, 6u, 100u, 200u, 747u, 748u, 1000u, 1494u, 1495u,
                                 1500u, 2000u, 2964u, 2966u, 3000u, 5000u, 5929u}) {
    const auto dtg = timers::dtg_for_ns(ns);
    ASSERT_TRUE(dtg.has_value()) << ns;
    const double back = dead_time_ns_from_dtg(*dtg, 0);
    const double tick_ns = 1e9 / kFtimHz;
    const double ticks_asked = ns / tick_ns;
    const double step = ticks_asked <= 127 ? 1 : ticks_asked <= 254 ? 2 : ticks_asked <= 504 ? 8 : 16;
    EXPECT_GE(back, ns - 1e-9) << ns;
    EXPECT_LT(back, ns + step * tick_ns) << ns;
  }
  EXPECT_FALSE(timers::dtg_for_ns(5930).has_value());
}

// The ADC trigger instant from CR2.MMS2, CCMR2.OC4M and CCR4: with TRGO2 = OC4REF and OC4 in PWM
// mode 2 (active while CNT >= CCR4 counting up, CNT > CCR4 counting down; RM0440 PWM-mode
// semantics), OC4REF rises once per period, when the up-count reaches CCR4. The period starts at
// CNT = 0 and lasts 2 ARR clocks; the top is its middle.
TEST(Stm32Timers, AdcTriggerFiresOncePerPeriodAtTheCounterTop) {
  for (const std::uint32_t hz : {timers::kPwm20kHz, timers::kPwm40kHz}) {
    RegisterFile rf;
    ASSERT_EQ(timers::init_bridge_pwm(rf, hz), Status::ok);
    ASSERT_EQ(field(rf, tim1::Cr2::reg, tim1::Cr2::MMS2), 0b0111u);  // TRGO2 = OC4REF
    const std::uint32_t oc4m = field(rf, tim1::Ccmr2::reg, tim1::Ccmr2::OC4M) |
                               field(rf, tim1::Ccmr2::reg, tim1::Ccmr2::OC4M_3) << 3;
    ASSERT_EQ(oc4m, 0b0111u);  // PWM mode 2
    EXPECT_EQ(field(rf, tim1::Ccer::reg, tim1::Ccer::CC4E), 0u);  // PA11 stays USB's
    const std::uint32_t arr = field(rf, tim1::Arr::reg, tim1::Arr::ARR);
    const std::uint32_t ccr4 = field(rf, tim1::Ccr4::reg, tim1::Ccr4::CCR4);
    // Walk one period clock by clock and find OC4REF's rising edges.
    int rising = 0;
    std::uint32_t edge_clock = 0;
    bool previous = false;
    for (std::uint32_t t = 0; t < 2 * arr; ++t) {
      const bool up = t < arr;
      const std::uint32_t cnt = up ? t : 2 * arr - t;
      const bool active = up ? cnt >= ccr4 : cnt > ccr4;
      if (active && !previous) {
        ++rising;
        edge_clock = t;
      }
      previous = active;
    }
    EXPECT_EQ(rising, 1);
    const double offset_ns = (static_cast<double>(edge_clock) - arr) * 1e9 / kFtimHz;
    EXPECT_LE(std::abs(offset_ns), 1e9 / kFtimHz + 1e-9) << "within one clock of the top";
    // At the top both legs at 0 V have their high side off (PWM mode 1: CNT >= CCRx).
    EXPECT_GE(arr, field(rf, tim1::Ccr1::reg, tim1::Ccr1::CCR1));
    EXPECT_EQ(field(rf, tim1::Ccr1::reg, tim1::Ccr1::CCR1), arr / 2);  // 0 V: equal duties
    EXPECT_EQ(field(rf, tim1::Ccr2::reg, tim1::Ccr2::CCR2), arr / 2);
  }
}

TEST(Stm32Timers, MainOutputEnableIsTheLastWriteAndOutputsIdleLow) {
  RegisterFile rf;
  ASSERT_EQ(timers::init_bridge_pwm(rf, timers::kPwm20kHz), Status::ok);
  const auto& log = rf.log();
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log.back().address, tim1::Bdtr::reg.address());
  EXPECT_EQ(tim1::Bdtr::MOE.decode(log.back().value), 1u);
  bool cen_before_moe = false;
  for (std::size_t i = 0; i + 1 < log.size(); ++i) {
    if (log[i].address == tim1::Bdtr::reg.address()) {
      EXPECT_EQ(tim1::Bdtr::MOE.decode(log[i].value), 0u) << "MOE set before the end, write " << i;
      EXPECT_EQ(log[i].value | tim1::Bdtr::MOE.mask(), log.back().value) << "BDTR changed";
    }
    if (log[i].address == tim1::Cr1::reg.address() && tim1::Cr1::CEN.decode(log[i].value) == 1) {
      cen_before_moe = true;
    }
  }
  EXPECT_TRUE(cen_before_moe);
  EXPECT_EQ(field(rf, tim1::Bdtr::reg, tim1::Bdtr::OSSI), 1u);
  EXPECT_EQ(field(rf, tim1::Bdtr::reg, tim1::Bdtr::OSSR), 1u);
  const std::uint32_t cr2 = rf.peek(tim1::Cr2::reg);
  for (const Field& ois : {tim1::Cr2::OIS1, tim1::Cr2::OIS1N, tim1::Cr2::OIS2, tim1::Cr2::OIS2N}) {
    EXPECT_EQ(ois.decode(cr2), 0u) << ois.name;
  }
  const std::uint32_t ccer = rf.peek(tim1::Ccer::reg);
  EXPECT_EQ(ccer, tim1::Ccer::CC1E.mask() | tim1::Ccer::CC1NE.mask() | tim1::Ccer::CC2E.mask() |
                      tim1::Ccer::CC2NE.mask());
  // Preload on CH1, CH2 (PWM mode 1).
  const std::uint32_t ccmr1 = rf.peek(tim1::Ccmr1::reg);
  EXPECT_EQ(tim1::Ccmr1::OC1M.decode(ccmr1) | tim1::Ccmr1::OC1M_3.decode(ccmr1) << 3, 0b0110u);
  EXPECT_EQ(tim1::Ccmr1::OC2M.decode(ccmr1) | tim1::Ccmr1::OC2M_3.decode(ccmr1) << 3, 0b0110u);
  EXPECT_EQ(tim1::Ccmr1::OC1PE.decode(ccmr1), 1u);
  EXPECT_EQ(tim1::Ccmr1::OC2PE.decode(ccmr1), 1u);
}

// Duty of leg A/B in % and the mean coil voltage (A - B) x supply they give.
TEST(Stm32Timers, CoilVoltageMapsToCentredBipolarDuty) {
  RegisterFile rf;
  ASSERT_EQ(timers::init_bridge_pwm(rf, timers::kPwm20kHz), Status::ok);
  const double arr = 4250;
  struct Case {
    float v;
    double duty_a;
    double duty_b;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const Case c : {Case{0.0f, 50, 50}, Case{24.0f, 100, 0}, Case{-24.0f, 0, 100},
                       Case{48.0f, 100, 0}, Case{-1e9f, 0, 100}, Case{nan, 50, 50},
                       Case{12.0f, 75, 25}, Case{-6.0f, 37.5, 62.5}}) {
    timers::set_coil_voltage(rf, c.v, 24.0f);
    const double a = 100.0 * field(rf, tim1::Ccr1::reg, tim1::Ccr1::CCR1) / arr;
    const double b = 100.0 * field(rf, tim1::Ccr2::reg, tim1::Ccr2::CCR2) / arr;
    EXPECT_NEAR(a, c.duty_a, 100.0 / arr) << c.v;  // within one count (0.024 %)
    EXPECT_NEAR(b, c.duty_b, 100.0 / arr) << c.v;
    const double v_mean = std::fmax(-24.0, std::fmin(24.0, std::isnan(c.v) ? 0.0 : c.v));
    EXPECT_NEAR((a - b) / 100.0 * 24.0, v_mean, 0.5 * 24.0 / arr) << c.v;  // half a step
  }
  // 40 kHz (ARR 2125, odd): 0 V is still exactly equal duties.
  const auto zero = timers::duty_for_voltage(0.0f, 24.0f, 2125);
  EXPECT_EQ(zero.ccr1, zero.ccr2);
  EXPECT_EQ(zero.ccr1, 1062u);
  const auto full = timers::duty_for_voltage(-24.0f, 24.0f, 2125);
  EXPECT_EQ(full.ccr1, 0u);
  EXPECT_EQ(full.ccr2, 2125u);
  // +V drives +z: leg A (coil +) above leg B.
  timers::set_coil_voltage(rf, 1.0f, 24.0f);
  EXPECT_GT(rf.peek(tim1::Ccr1::reg), rf.peek(tim1::Ccr2::reg));
  // No usable supply: 0 V.
  for (const float supply : {0.0f, -24.0f, nan}) {
    const auto d = timers::duty_for_voltage(10.0f, supply, 4250);
    EXPECT_EQ(d.ccr1, 2125u);
    EXPECT_EQ(d.ccr2, 2125u);
  }
}

// The facts-sheet IC filter table (§4.3): code -> (sampling divider of f_CK_INT, N samples).
struct Filter {
  double divider;
  int n;
};
Filter ic_filter(std::uint32_t code) {
  constexpr Filter table[16] = {{1, 1},  {1, 2},  {1, 4},  {1, 8},  {2, 6},  {2, 8},
                                {4, 6},  {4, 8},  {8, 6},  {8, 8},  {16, 5}, {16, 6},
                                {16, 8}, {32, 5}, {32, 6}, {32, 8}};
  return table[code & 0xF];
}

// A count rate r puts edges 1/r apart; the filter's window (N samples) must be at most half of
// that, so it passes count rates up to 1 / (2 window).
TEST(Stm32Timers, EncoderFilterPassesTheFiveMegahertzCountRate) {
  RegisterFile rf;
  timers::init_encoder(rf);
  const std::uint32_t ccmr1 = rf.peek(tim2::Ccmr1::reg);
  EXPECT_EQ(tim2::Ccmr1::CC1S.decode(ccmr1), 1u);
  EXPECT_EQ(tim2::Ccmr1::CC2S.decode(ccmr1), 1u);
  for (const Field& f : {tim2::Ccmr1::IC1F, tim2::Ccmr1::IC2F}) {
    const Filter filter = ic_filter(f.decode(ccmr1));
    const double window_s = filter.n * filter.divider / kFtimHz;
    const double pass_hz = 1.0 / (2.0 * window_s);
    EXPECT_GE(pass_hz, 5e6) << f.name;  // 5 m/s at 1 um per count
    EXPECT_NEAR(window_s * 1e9, 94.1, 0.05) << f.name;
  }
  const std::uint32_t smcr = rf.peek(tim2::Smcr::reg);
  EXPECT_EQ(tim2::Smcr::SMS.decode(smcr) | tim2::Smcr::SMS_3.decode(smcr) << 3, 0b0011u);
  EXPECT_EQ(rf.peek(tim2::Arr::reg), 0xFFFF'FFFFu);
  EXPECT_EQ(rf.peek(tim2::Ccer::reg), 0u);
  EXPECT_EQ(field(rf, tim2::Cr1::reg, tim2::Cr1::CEN), 1u);
  EXPECT_EQ(field(rf, rcc::Apb1enr1::reg, rcc::Apb1enr1::TIM2EN), 1u);
}

TEST(Stm32Timers, EncoderCountIsTheLow16BitsAndWrapsLikeA16BitTimer) {
  RegisterFile rf;
  rf.poke(tim2::Cnt::reg, 0x0001'FFFEu);
  EXPECT_EQ(timers::encoder_count16(rf), 0xFFFEu);
  rf.poke(tim2::Cnt::reg, 0xFFFF'FFFFu);  // -1 as int32
  EXPECT_EQ(timers::encoder_count16(rf), 0xFFFFu);
  // +3 counts across the 32-bit wrap: the 16-bit difference is still 3.
  rf.poke(tim2::Cnt::reg, 0xFFFF'FFFEu);
  const std::uint16_t before = timers::encoder_count16(rf);
  rf.poke(tim2::Cnt::reg, 0x0000'0001u);
  EXPECT_EQ(static_cast<std::uint16_t>(timers::encoder_count16(rf) - before), 3u);
}

TEST(Stm32Timers, WatchdogTimeoutFromPrAndRlrLiesIn50To100MsOverTheLsiBand) {
  RegisterFile rf;
  ASSERT_EQ(timers::start_watchdog(rf), Status::ok);
  const double clocks = (field(rf, iwdg::Rlr::reg, iwdg::Rlr::RL) + 1.0) *
                        (4u << field(rf, iwdg::Pr::reg, iwdg::Pr::PR));
  EXPECT_NEAR(clocks / timers::kLsiNominalHz * 1e3, 75.0, 1e-9);
  const double min_ms = clocks / timers::kLsiAssumedMaxHz * 1e3;
  const double max_ms = clocks / timers::kLsiAssumedMinHz * 1e3;
  EXPECT_NEAR(min_ms, 68.18, 0.01);
  EXPECT_NEAR(max_ms, 83.33, 0.01);
  EXPECT_GE(min_ms, 50.0);
  EXPECT_LE(max_ms, 100.0);
  // Key sequence: start, unlock, PR, RLR, ..., reload last.
  const auto& log = rf.log();
  ASSERT_EQ(log.size(), 5u);
  EXPECT_EQ(log[0].address, iwdg::Kr::reg.address());
  EXPECT_EQ(log[0].value, 0xCCCCu);
  EXPECT_EQ(log[1].value, 0x5555u);
  EXPECT_EQ(log[2].address, iwdg::Pr::reg.address());
  EXPECT_EQ(log[3].address, iwdg::Rlr::reg.address());
  EXPECT_EQ(log[4].address, iwdg::Kr::reg.address());
  EXPECT_EQ(log[4].value, 0xAAAAu);
}

TEST(Stm32Timers, WatchdogWhoseUpdateNeverEndsIsReported) {
  RegisterFile rf;
  rf.poke(iwdg::Sr::reg, iwdg::Sr::RVU.mask());
  EXPECT_EQ(timers::start_watchdog(rf), Status::watchdog_not_updated);
}

}  // namespace
}  // namespace palp::stm32
