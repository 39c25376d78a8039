// SPDX-License-Identifier: Apache-2.0
// The clock init (firmware/board/stm32g474/clock.hpp) run on a host register file: the clocks
// are COMPUTED from the register values it leaves (SYSCLK from source, M, N, R and the switch
// status; HCLK from HPRE; the flash wait states the result needs in boost or normal mode; the
// 48 MHz USB clock and its CRS sync) and compared with what the board promises; the order of the
// writes that matter is checked on the write log.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "clock.hpp"
#include "register_file.hpp"

namespace palp::stm32 {
namespace {

using Lines = std::vector<std::string>;
using test::RegisterFile;
using test::Write;

struct ClockTree {
  std::uint32_t sysclk_hz = 0;
  std::uint32_t hclk_hz = 0;
  std::uint32_t pll_input_hz = 0;
  std::uint32_t vco_hz = 0;
};

// SYSCLK from the switch status (SWS), not from what was requested (SW).
ClockTree compute_clock_tree(const RegisterFile& rf) {
  using namespace rcc;
  ClockTree tree;
  const std::uint32_t cfgr = rf.peek(Cfgr::reg);
  const std::uint32_t sws = Cfgr::SWS.decode(cfgr);
  if (sws == Cfgr::kSwHsi16) {
    tree.sysclk_hz = clock::kHsi16Hz;
  } else if (sws == Cfgr::kSwPll) {
    const std::uint32_t pll = rf.peek(Pllcfgr::reg);
    const std::uint32_t cr = rf.peek(Cr::reg);
    const bool source_hsi16 = Pllcfgr::PLLSRC.decode(pll) == Pllcfgr::kSrcHsi16 &&
                              Cr::HSIRDY.decode(cr) == 1;
    const bool running = Cr::PLLON.decode(cr) == 1 && Cr::PLLRDY.decode(cr) == 1 &&
                         Pllcfgr::PLLREN.decode(pll) == 1;
    if (source_hsi16 && running) {
      tree.pll_input_hz = clock::kHsi16Hz / (Pllcfgr::PLLM.decode(pll) + 1);
      tree.vco_hz = tree.pll_input_hz * Pllcfgr::PLLN.decode(pll);
      tree.sysclk_hz = tree.vco_hz / (2 * (Pllcfgr::PLLR.decode(pll) + 1));
    }
  }
  const std::uint32_t hpre = Cfgr::HPRE.decode(cfgr);
  const std::uint32_t hpre_divisor[] = {2, 4, 8, 16, 64, 128, 256, 512};  // HPRE 1000..1111
  tree.hclk_hz = hpre < 8 ? tree.sysclk_hz : tree.sysclk_hz / hpre_divisor[hpre - 8];
  return tree;
}

// The fewest flash wait states for `hclk_hz` (facts §3.2 wait-state table), or nothing above
// the range's limit.
std::optional<std::uint32_t> wait_states_needed(std::uint32_t hclk_hz, bool boost) {
  const std::uint32_t boost_max_mhz[] = {34, 68, 102, 136, 170};
  const std::uint32_t normal_max_mhz[] = {30, 60, 90, 120, 150};
  for (std::uint32_t ws = 0; ws < 5; ++ws) {
    if (hclk_hz <= (boost ? boost_max_mhz : normal_max_mhz)[ws] * 1'000'000u) {
      return ws;
    }
  }
  return std::nullopt;
}

// The 48 MHz USB clock if HSI48 runs and is selected (facts §3.1 CLK48SEL, §3.3), else 0.
std::uint32_t usb_clock_hz(const RegisterFile& rf) {
  const std::uint32_t crrcr = rf.peek(rcc::Crrcr::reg);
  const bool hsi48 = rcc::Crrcr::HSI48ON.decode(crrcr) == 1 && rcc::Crrcr::HSI48RDY.decode(crrcr) == 1;
  const bool selected =
      rcc::Ccipr::CLK48SEL.decode(rf.peek(rcc::Ccipr::reg)) == rcc::Ccipr::kClk48Hsi48;
  return hsi48 && selected ? 48'000'000u : 0u;
}

template <class Predicate>
std::optional<std::size_t> first_write(const std::vector<Write>& log, const Register& reg,
                                       Predicate predicate) {
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (log[i].address == reg.address() && predicate(log[i].value)) {
      return i;
    }
  }
  return std::nullopt;
}

// The orderings facts §3.2 requires, as violations found in a write log.
Lines order_violations(const std::vector<Write>& log) {
  using rcc::Cfgr;
  const auto to_pll = first_write(log, Cfgr::reg, [](std::uint32_t v) {
    return Cfgr::SW.decode(v) == Cfgr::kSwPll;
  });
  if (!to_pll) {
    return {"RCC_CFGR.SW is never set to the PLL"};
  }
  Lines violations;
  const auto wait_states = first_write(log, flash::Acr::reg, [](std::uint32_t v) {
    return flash::Acr::LATENCY.decode(v) >= clock::kFlashLatency;
  });
  if (!wait_states || *wait_states > *to_pll) {
    violations.push_back("FLASH_ACR.LATENCY >= 4 is not written before RCC_CFGR.SW = PLL");
  }
  const auto boost = first_write(log, pwr::Cr5::reg, [](std::uint32_t v) {
    return pwr::Cr5::R1MODE.decode(v) == 0;
  });
  if (!boost || *boost > *to_pll) {
    violations.push_back("PWR_CR5.R1MODE = 0 (boost) is not written before RCC_CFGR.SW = PLL");
  }
  if (Cfgr::HPRE.decode(log[*to_pll].value) != Cfgr::kHpreDiv2) {
    violations.push_back("RCC_CFGR.SW = PLL is written with AHB not at /2");
  }
  return violations;
}

TEST(Stm32Clock, InitLeavesSysclkAndHclkAt170MHzFromHsi16ThroughThePll) {
  RegisterFile rf;
  ASSERT_EQ(clock::init(rf), clock::Status::ok);
  const ClockTree tree = compute_clock_tree(rf);
  EXPECT_EQ(tree.sysclk_hz, 170'000'000u);
  EXPECT_EQ(tree.hclk_hz, clock::kSysclkHz);
  // PLL limits (facts §3.1): input 2.66..16 MHz, VCO 96..344 MHz.
  EXPECT_EQ(tree.pll_input_hz, 4'000'000u);
  EXPECT_EQ(tree.vco_hz, 340'000'000u);
  EXPECT_EQ(rcc::Cfgr::PPRE1.decode(rf.peek(rcc::Cfgr::reg)), 0u);  // APB1 /1
  EXPECT_EQ(rcc::Cfgr::PPRE2.decode(rf.peek(rcc::Cfgr::reg)), 0u);  // APB2 /1
}

TEST(Stm32Clock, FlashWaitStatesSufficeFor170MHzOnlyInBoostModeWhichInitSets) {
  RegisterFile rf;
  ASSERT_EQ(clock::init(rf), clock::Status::ok);
  const bool boost = pwr::Cr5::R1MODE.decode(rf.peek(pwr::Cr5::reg)) == 0;
  EXPECT_TRUE(boost);
  EXPECT_EQ(pwr::Cr1::VOS.decode(rf.peek(pwr::Cr1::reg)), pwr::Cr1::kVosRange1);
  const std::uint32_t acr = rf.peek(flash::Acr::reg);
  const auto needed = wait_states_needed(compute_clock_tree(rf).hclk_hz, boost);
  ASSERT_TRUE(needed.has_value());
  EXPECT_EQ(*needed, 4u);
  EXPECT_GE(flash::Acr::LATENCY.decode(acr), *needed);
  EXPECT_EQ(wait_states_needed(170'000'000, false), std::nullopt);  // normal mode tops at 150
  EXPECT_EQ(flash::Acr::PRFTEN.decode(acr), 1u);
  EXPECT_EQ(flash::Acr::ICEN.decode(acr), 1u);
  EXPECT_EQ(flash::Acr::DCEN.decode(acr), 1u);
}

TEST(Stm32Clock, UsbClockIs48MHzFromHsi48TrimmedByCrsToUsbSof) {
  RegisterFile rf;
  ASSERT_EQ(clock::init(rf), clock::Status::ok);
  EXPECT_EQ(usb_clock_hz(rf), clock::kUsbClockHz);
  EXPECT_EQ(rcc::Apb1enr1::CRSEN.decode(rf.peek(rcc::Apb1enr1::reg)), 1u);
  const std::uint32_t cr = rf.peek(crs::Cr::reg);
  EXPECT_EQ(crs::Cr::CEN.decode(cr), 1u);
  EXPECT_EQ(crs::Cr::AUTOTRIMEN.decode(cr), 1u);
  const std::uint32_t cfgr = rf.peek(crs::Cfgr::reg);
  EXPECT_EQ(crs::Cfgr::SYNCSRC.decode(cfgr), crs::Cfgr::kSyncSrcUsbSof);
  EXPECT_EQ(crs::Cfgr::SYNCDIV.decode(cfgr), 0u);
  // The sync it expects: 48 MHz / (RELOAD + 1) = 1 kHz, the USB full-speed SOF rate.
  EXPECT_EQ(clock::kUsbClockHz / (crs::Cfgr::RELOAD.decode(cfgr) + 1), 1'000u);
}

TEST(Stm32Clock, WaitStatesAndBoostAreWrittenBeforeTheSwitchWhichHappensAtAhbDiv2) {
  RegisterFile rf;
  ASSERT_EQ(clock::init(rf), clock::Status::ok);
  EXPECT_EQ(order_violations(rf.log()), Lines{});
}

TEST(Stm32Clock, TheOrderCheckCatchesWaitStatesWrittenAfterTheSwitch) {
  const std::uint32_t switch_at_div2 = rcc::Cfgr::SW.encode(rcc::Cfgr::kSwPll) |
                                       rcc::Cfgr::HPRE.encode(rcc::Cfgr::kHpreDiv2);
  const std::vector<Write> log = {
      {pwr::Cr5::reg.address(), 0},
      {rcc::Cfgr::reg.address(), switch_at_div2},
      {flash::Acr::reg.address(), flash::Acr::LATENCY.encode(4)},
  };
  EXPECT_EQ(order_violations(log),
            Lines{"FLASH_ACR.LATENCY >= 4 is not written before RCC_CFGR.SW = PLL"});
  const std::vector<Write> no_boost_no_div2 = {
      {flash::Acr::reg.address(), flash::Acr::LATENCY.encode(4)},
      {rcc::Cfgr::reg.address(), rcc::Cfgr::SW.encode(rcc::Cfgr::kSwPll)},
  };
  EXPECT_EQ(order_violations(no_boost_no_div2),
            (Lines{"PWR_CR5.R1MODE = 0 (boost) is not written before RCC_CFGR.SW = PLL",
                   "RCC_CFGR.SW = PLL is written with AHB not at /2"}));
}

TEST(Stm32Clock, APllThatNeverLocksStopsInitBeforeTheSwitch) {
  RegisterFile rf;
  rf.set_hardware_reacts(false);
  EXPECT_EQ(clock::init(rf), clock::Status::pll_not_ready);
  EXPECT_EQ(rcc::Cfgr::SW.decode(rf.peek(rcc::Cfgr::reg)), rcc::Cfgr::kSwHsi16);
  EXPECT_EQ(compute_clock_tree(rf).sysclk_hz, clock::kHsi16Hz);
}

TEST(Stm32Clock, AnHsi48ThatNeverStartsIsReportedAndCrsStaysOff) {
  RegisterFile rf;
  ASSERT_EQ(clock::init_sysclk_170mhz(rf), clock::Status::ok);
  rf.set_hardware_reacts(false);
  EXPECT_EQ(clock::init_usb_clock_48mhz(rf), clock::Status::hsi48_not_ready);
  EXPECT_EQ(crs::Cr::CEN.decode(rf.peek(crs::Cr::reg)), 0u);
  EXPECT_EQ(usb_clock_hz(rf), 0u);
}

}  // namespace
}  // namespace palp::stm32
