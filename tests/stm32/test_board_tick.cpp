// SPDX-License-Identifier: Apache-2.0
// The STM32G474 board class's control tick (stm_board.hpp) on a host register file: the rate the
// registers make, the inputs one end-of-sequence interrupt delivers from known codes, the outputs
// it writes, the tick's mask, missed ticks on the µs grid and the µs clock across its wrap.
// Expected values are computed from the README's transfers and the facts sheet, not the code's.
#include <cmath>
#include <cstdint>

#include "board_fixture.hpp"

namespace palp::stm32::board_test {
namespace {

constexpr std::uint32_t kIcer0 = 0xE000E180u;  // ARMv7-M ARM B3.4.5
constexpr std::uint32_t kIser0 = 0xE000E100u;  // B3.4.4
constexpr std::uint32_t kBit18 = 1u << 18;

/// The PWM frequency the TIM1 registers make: centre-aligned, f_tim / ((PSC + 1) x 2 ARR).
double pwm_hz(const BoardHardware& hw) {
  EXPECT_NE(hw.field(tim1::Cr1::reg, tim1::Cr1::CMS), 0u) << "centre-aligned";
  EXPECT_EQ(hw.field(tim1::Cr1::reg, tim1::Cr1::CEN), 1u);
  const double psc = hw.field(tim1::Psc::reg, tim1::Psc::PSC);
  const double arr = hw.field(tim1::Arr::reg, tim1::Arr::ARR);
  return 170e6 / ((psc + 1.0) * 2.0 * arr);
}

class StmBoardTick : public BoardTest {};

TEST_F(StmBoardTick, StartTickAt20And40kHzLeavesTim1PwmAndTheAdcTriggerAtThatRate) {
  for (const std::uint32_t rate : {20'000u, 40'000u}) {
    ASSERT_TRUE(board.start_tick(rate, handler()));
    EXPECT_DOUBLE_EQ(pwm_hz(hw), rate);
    EXPECT_EQ(hw.field(tim1::Bdtr::reg, tim1::Bdtr::MOE), 1u);
    // TRGO2 = OC4REF one clock before the top (timers.hpp); ADC1 converts on it, JEOS interrupt.
    EXPECT_EQ(hw.field(tim1::Cr2::reg, tim1::Cr2::MMS2), 0b0111u);
    EXPECT_EQ(hw.peek(tim1::Ccr4::reg), hw.peek(tim1::Arr::reg) - 1);
    EXPECT_EQ(hw.field(adc::Jsqr::adc1, adc::Jsqr::JEXTSEL), 8u);  // facts §4.4: TIM1_TRGO2
    EXPECT_EQ(hw.field(adc::Jsqr::adc1, adc::Jsqr::JEXTEN), 1u);
    EXPECT_EQ(hw.field(adc::Ier::adc1, adc::Ier::JEOSIE), 1u);
    EXPECT_EQ(hw.field(adc::Cr::adc1, adc::Cr::JADSTART), 1u);
  }
  // IRQ 18 enabled, priority byte 2 of IPR4 = 0x40; LPUART (91) byte 3 of IPR22 = 0x80: lower.
  EXPECT_GT(hw.count_writes(kIser0, kBit18), 0u);
  EXPECT_EQ((hw.peek(0xE000E400u + 4 * 4) >> 16) & 0xFF, 0x40u);
  EXPECT_EQ((hw.peek(0xE000E400u + 4 * 22) >> 24) & 0xFF, 0x80u);
  EXPECT_EQ(hw.peek(0xE000E100u + 4 * 2), 1u << (91 - 64)) << "the link's interrupt is enabled";
}

TEST_F(StmBoardTick, ARejectedRateOrNoHandlerWritesNothingAndReturnsFalse) {
  const std::size_t before = hw.log_size();
  for (const std::uint32_t rate : {0u, 10'000u, 19'999u, 25'000u, 40'001u, 80'000u}) {
    EXPECT_FALSE(board.start_tick(rate, handler())) << rate;
  }
  EXPECT_FALSE(board.start_tick(20'000, app::TickHandler{}));
  EXPECT_EQ(hw.log_size(), before);
}

TEST_F(StmBoardTick, OneEndOfSequenceInterruptDeliversTheInputsOfTheKnownCodes) {
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  hw.poke(adc::Jdr1::adc1, 3277);  // README §5: 3 A -> code 3277
  hw.poke(adc::Jdr2::adc1, 2258);  // README §5: 24 V -> code 2258
  hw.poke(tim2::Cnt::reg, 0x0003'1234);
  pressure = {411, 2055, 3699, 0, 4095, 1};
  hw.poke(gpio::IdrC::reg, 0);  // nFAULT asserted (low)
  tick_at(25);
  ASSERT_EQ(inputs.size(), 1u);
  const fw::TickInputs& in = inputs[0];
  // (3277 - 2048) x 3.3 / 4096 / 0.33 = 3.0005 A; 2258 x 3.3 / 4096 x 108.2 / 8.2 = 24.005 V.
  EXPECT_NEAR(in.i_sense_A, 3.0005f, 0.001f);
  EXPECT_NEAR(in.supply_V, 24.005f, 0.01f);
  EXPECT_EQ(in.encoder_timer, 0x1234);
  EXPECT_EQ(in.pressure_codes, (fw::PressureChannels::Codes{411, 2055, 3699, 0, 4095, 1}));
  EXPECT_TRUE(in.driver_fault);
  EXPECT_EQ(in.missed_ticks, 0u);
  EXPECT_EQ(hw.peek(adc::Isr::adc1) & (adc::Isr::JEOC.mask() | adc::Isr::JEOS.mask()), 0u)
      << "the interrupt's flags are cleared";

  hw.poke(adc::Jdr1::adc1, 2048);  // 0 A at mid-rail; nFAULT released
  hw.poke(gpio::IdrC::reg, gpio::IdrC::IDR10.mask());
  tick_at(75);
  EXPECT_FLOAT_EQ(inputs[1].i_sense_A, 0.0f);
  EXPECT_FALSE(inputs[1].driver_fault);
}

TEST_F(StmBoardTick, ApplyOutputsWritesTheBridgeDutyForTheMeasuredSupplyAndTheContactLine) {
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  hw.poke(adc::Jdr2::adc1, 1882);  // 1882 x 3.3 / 4096 x 108.2 / 8.2 = 20.007 V, not 24 V
  outputs.v_coil_V = 12.0f;
  outputs.contact_line = true;
  const std::size_t from = hw.log_size();
  tick_at(25);
  // 12 / 20.007 x 4250 = 2549.1 -> 2549 counts between the legs, centred on 2125:
  // CCR1 = (4250 + 2549) / 2 = 3399, CCR2 = 3399 - 2549 = 850.
  EXPECT_EQ(hw.peek(tim1::Ccr1::reg), 3399u);
  EXPECT_EQ(hw.peek(tim1::Ccr2::reg), 850u);
  EXPECT_EQ(hw.count_writes(gpio::BsrrC::reg.address(), 1u << 6, from), 1u) << "PC6 set";
  std::size_t adstarts = 0;
  for (const test::Write& w : hw.writes_since(from)) {
    adstarts += w.address == adc::Cr::adc2.address() && adc::Cr::ADSTART.decode(w.value) == 1;
  }
  EXPECT_EQ(adstarts, 1u) << "one ADC2 ADSTART: the next pressure scan";

  outputs.v_coil_V = -6.0f;
  outputs.contact_line = false;
  const std::size_t from2 = hw.log_size();
  tick_at(75);
  // -6 / 20.007 x 4250 = -1274.54 -> -1275: CCR1 = (4250 - 1275) / 2 = 1487, CCR2 = 2762.
  EXPECT_EQ(hw.peek(tim1::Ccr1::reg), 1487u);
  EXPECT_EQ(hw.peek(tim1::Ccr2::reg), 2762u);
  EXPECT_EQ(hw.count_writes(gpio::BsrrC::reg.address(), 1u << (16 + 6), from2), 1u) << "PC6 reset";
}

TEST_F(StmBoardTick, HoldTickWritesIcerBit18OnlyAndNestedHoldsReleaseAtTheOutermost) {
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  std::size_t from = hw.log_size();
  board.hold_tick();
  ASSERT_EQ(hw.writes_since(from).size(), 1u);
  EXPECT_EQ(hw.writes_since(from)[0].address, kIcer0);
  EXPECT_EQ(hw.writes_since(from)[0].value, kBit18);

  board.hold_tick();  // nested (the core's guard inside the app's rate change)
  from = hw.log_size();
  board.release_tick();
  EXPECT_EQ(hw.count_writes(kIser0, kBit18, from), 0u) << "still held by the outer hold";
  board.release_tick();
  ASSERT_EQ(hw.writes_since(from).size(), 1u);
  EXPECT_EQ(hw.writes_since(from)[0].address, kIser0);
  EXPECT_EQ(hw.writes_since(from)[0].value, kBit18);
}

TEST_F(StmBoardTick, StartTickWhileHeldLeavesTheTickMaskedUntilRelease) {
  board.hold_tick();
  const std::size_t from = hw.log_size();
  ASSERT_TRUE(board.start_tick(40'000, handler()));
  EXPECT_EQ(hw.count_writes(kIser0, kBit18, from), 0u);
  board.release_tick();
  EXPECT_EQ(hw.count_writes(kIser0, kBit18, from), 1u);
}

TEST_F(StmBoardTick, ARateChangeTurnsEveryGateOffBeforeReprogrammingAndEndsAtZeroVolts) {
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  hw.poke(adc::Jdr2::adc1, 2258);
  outputs.v_coil_V = 20.0f;
  tick_at(25);
  ASSERT_NE(hw.peek(tim1::Ccr1::reg), hw.peek(tim1::Ccr2::reg));
  const std::size_t from = hw.log_size();
  ASSERT_TRUE(board.start_tick(40'000, handler()));
  // The first TIM1 write of the change clears MOE; MOE is set again once, in TIM1's last write.
  const std::vector<test::Write> w = hw.writes_since(from);
  std::vector<std::size_t> tim1_writes, moe_on;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (w[k].address >= tim::kTim1Base && w[k].address < tim::kTim1Base + 0x400) {
      tim1_writes.push_back(k);
    }
    if (w[k].address == tim1::Bdtr::reg.address() && tim1::Bdtr::MOE.decode(w[k].value) == 1) {
      moe_on.push_back(k);
    }
  }
  ASSERT_FALSE(tim1_writes.empty());
  EXPECT_EQ(w[tim1_writes.front()].address, tim1::Bdtr::reg.address());
  EXPECT_EQ(tim1::Bdtr::MOE.decode(w[tim1_writes.front()].value), 0u);
  ASSERT_EQ(moe_on.size(), 1u);
  EXPECT_EQ(moe_on[0], tim1_writes.back());
  EXPECT_DOUBLE_EQ(pwm_hz(hw), 40'000.0);
  EXPECT_EQ(hw.peek(tim1::Ccr1::reg), hw.peek(tim1::Ccr2::reg)) << "0 V until the next tick";
}

TEST_F(StmBoardTick, MissedTicksCountGridTicksThatFellDueWithoutAnInterruptOnce) {
  hw.poke(tim5::Cnt::reg, 1000);
  ASSERT_TRUE(board.start_tick(20'000, handler()));  // grid: 1000 + 50 k, due from +0
  tick_at(1000 + 27);  // tick 1 (half a period after the start, a little late)
  tick_at(1000 + 76);  // tick 2
  tick_at(1000 + 276);  // ticks 3, 4, 5 fell due at +100, +150, +200; this is tick 6
  tick_at(1000 + 326);  // tick 7
  ASSERT_EQ(inputs.size(), 4u);
  EXPECT_EQ(inputs[0].missed_ticks, 0u);
  EXPECT_EQ(inputs[1].missed_ticks, 0u);
  EXPECT_EQ(inputs[2].missed_ticks, 3u);
  EXPECT_EQ(inputs[3].missed_ticks, 0u) << "reported once";
  tick_at(1000 + 326 + 10);  // an extra interrupt within the same period is no missed tick
  EXPECT_EQ(inputs[4].missed_ticks, 0u);
}

TEST_F(StmBoardTick, NowUsIsTim5ExtendedTo64BitsAndMonotonicAcrossItsWrap) {
  hw.poke(tim5::Cnt::reg, 0xFFFF'FFF0u);
  const std::uint64_t a = board.now_us();
  EXPECT_EQ(a, 0xFFFF'FFF0u);
  hw.poke(tim5::Cnt::reg, 0x0000'0010u);  // 32 µs later, past the wrap
  const std::uint64_t b = board.now_us();
  EXPECT_EQ(b, a + 0x20);
  EXPECT_EQ(board.now_us(), b);
  // TIM5 counts µs: PSC = 170 - 1 at 170 MHz, ARR = 2^32 - 1, running.
  EXPECT_EQ(170e6 / (hw.field(tim5::Psc::reg, tim5::Psc::PSC) + 1.0), 1e6);
  EXPECT_EQ(hw.peek(tim5::Arr::reg), 0xFFFF'FFFFu);
  EXPECT_EQ(hw.field(tim5::Cr1::reg, tim5::Cr1::CEN), 1u);
  EXPECT_EQ(hw.field(rcc::Apb1enr1::reg, rcc::Apb1enr1::TIM5EN), 1u);
}

}  // namespace
}  // namespace palp::stm32::board_test
