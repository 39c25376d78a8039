// SPDX-License-Identifier: Apache-2.0
// The STM32G474 board class (stm_board.hpp) around its tick, on a host register file: the IWDG
// refresh rule, the bootloader request, the identity from the device UID, the link's transmit
// wake-up, idle()'s sleep and the status LED (calibration storage: test_board_calibration.cpp;
// the USB link: test_board_usb.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "board_fixture.hpp"

namespace palp::stm32::board_test {
namespace {

class StmBoardSystem : public BoardTest {
 protected:
  std::size_t watchdog_reloads(std::size_t from) const {
    return hw.count_writes(iwdg::Kr::reg.address(), iwdg::Kr::kReload, from);
  }
  static bool no_work(void*) { return false; }
  static bool work(void*) { return true; }
};

TEST_F(StmBoardSystem, TheWatchdogStartsWithTheTickNotAtInit) {
  EXPECT_EQ(hw.count_writes(iwdg::Kr::reg.address(), iwdg::Kr::kStart), 0u);
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  EXPECT_EQ(hw.count_writes(iwdg::Kr::reg.address(), iwdg::Kr::kStart), 1u);
  ASSERT_TRUE(board.start_tick(40'000, handler()));  // a rate change does not restart it
  EXPECT_EQ(hw.count_writes(iwdg::Kr::reg.address(), iwdg::Kr::kStart), 1u);
}

TEST_F(StmBoardSystem, TheTickRefreshesTheWatchdogOnlyWhileTheMainLoopShowsLife) {
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  std::uint64_t t = 25;
  // 100 ms of ticks with the main loop passing idle() every tick: refreshed every tick.
  std::size_t from = hw.log_size();
  for (int k = 0; k < 2000; ++k, t += 50) {
    tick_at(t);
    board.idle(&StmBoardSystem::work, nullptr);
  }
  EXPECT_EQ(watchdog_reloads(from), 2000u);
  // The main loop stalls (no idle()): the tick refreshes for 50 ms more, then never again.
  const std::uint64_t stalled_at = t;  // the first tick after the main loop's last idle()
  from = hw.log_size();
  std::size_t last_refresh_tick = 0;
  for (int k = 0; k < 4000; ++k, t += 50) {
    const std::size_t before = watchdog_reloads(0);
    tick_at(t);
    if (watchdog_reloads(0) > before) last_refresh_tick = static_cast<std::size_t>(t);
  }
  EXPECT_EQ(last_refresh_tick, stalled_at + 50'000) << "the 50 ms window, not longer";
  EXPECT_EQ(watchdog_reloads(from), 1001u);  // 100.025 .. 150.025 ms, every 50 µs
  // The main loop comes back: refreshes resume.
  board.idle(&StmBoardSystem::work, nullptr);
  from = hw.log_size();
  tick_at(t);
  EXPECT_EQ(watchdog_reloads(from), 1u);
}

TEST_F(StmBoardSystem, EnterBootloaderWritesTheRequestThenSysResetReqAndWaitsForTheReset) {
  const std::size_t from = hw.log_size();
  board.enter_bootloader();
  const std::vector<test::Write> w = hw.writes_since(from);
  std::size_t word0 = w.size(), word1 = w.size(), aircr = w.size();
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (w[k].address == kRequestAddress) word0 = k;
    if (w[k].address == kRequestAddress + 4) word1 = k;
    if (w[k].address == 0xE000ED0Cu) aircr = k;  // ARMv7-M ARM B3.2.6 AIRCR
  }
  ASSERT_LT(aircr, w.size());
  EXPECT_EQ(w[aircr].value, 0x05FA'0004u) << "VECTKEY | SYSRESETREQ";
  EXPECT_LT(word0, aircr);
  EXPECT_LT(word1, aircr);
  EXPECT_EQ(hw.peek(kRequestAddress), bootloader::kRequestWord0);
  EXPECT_EQ(hw.peek(kRequestAddress + 4), bootloader::kRequestWord1);
  EXPECT_EQ(hw.count_writes(gpio::BsrrC::reg.address(), 1u << (16 + 11), from), 1u)
      << "the driver's ENABLE (PC11) goes low first";
  ASSERT_FALSE(cpu.events.empty());
  EXPECT_EQ(cpu.events.back(), "wait_for_reset");
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&bootloader::kRequestWord0), 4), "PALP");
}

TEST_F(StmBoardSystem, IdentityNamesTheBoardTheUidSerialTheGitHashAndTheLinkStreamRate) {
  BoardHardware fresh;
  fresh.poke(StmBoardT<BoardHardware, RecordingCpu>::kUidBase, 0x0012'ABCDu);  // facts §1.1
  fresh.poke(0x1FFF'7594u, 0x3433'3231u);
  fresh.poke(0x1FFF'7598u, 0xFEDC'BA98u);
  Board::Link fresh_link(fresh);
  Board b(fresh, cpu, fresh_link, platform());
  b.init();
  const fw::DeviceIdentity id = b.identity();
  EXPECT_STREQ(id.board, "stm32g474");  // proto::board_name(BoardId::stm32g474)
  EXPECT_STREQ(id.serial, "0012ABCD34333231FEDCBA98");
  EXPECT_STREQ(id.git_hash, "abc1234");
  EXPECT_EQ(id.max_stream_rate_Hz, 3840u);  // 921600 baud / 10 / 24 B per sample
}

TEST_F(StmBoardSystem, LinkWriteArmsTheTxInterruptOnlyWhenTheFifoIsFullAndTheIsrDisarmsIt) {
  const std::uint8_t bytes[3] = {1, 2, 3};
  EXPECT_EQ(board.link_write(bytes, 3), 3u);  // the model's FIFO always has room
  EXPECT_EQ(hw.field(lpuart1::Cr1::reg, lpuart1::Cr1::TXEIE), 0u);

  hw.poke(lpuart1::Isr::reg, 0);  // TX FIFO full
  EXPECT_EQ(board.link_write(bytes, 3), 0u);
  EXPECT_EQ(hw.field(lpuart1::Cr1::reg, lpuart1::Cr1::TXEIE), 1u) << "armed: wakes idle()";
  EXPECT_EQ(hw.field(lpuart1::Cr1::reg, lpuart1::Cr1::RXNEIE), 1u) << "RX left on";

  hw.poke(lpuart1::Isr::reg, lpuart1::Isr::TXE.mask());  // room again: the interrupt comes
  board.link().on_irq();
  EXPECT_EQ(hw.field(lpuart1::Cr1::reg, lpuart1::Cr1::TXEIE), 0u) << "the ISR disarms it";
  EXPECT_EQ(hw.field(lpuart1::Cr1::reg, lpuart1::Cr1::RXNEIE), 1u);
}

TEST_F(StmBoardSystem, IdleSleepsWithInterruptsMaskedOnlyWhenThereIsNoWork) {
  cpu.events.clear();
  board.idle(&StmBoardSystem::no_work, nullptr);
  EXPECT_EQ(cpu.events, (std::vector<std::string>{"cpsid", "wfi (masked)", "cpsie"}));
  cpu.events.clear();
  board.idle(&StmBoardSystem::work, nullptr);
  EXPECT_EQ(cpu.events, (std::vector<std::string>{"cpsid", "cpsie"}));
}

TEST_F(StmBoardSystem, TheStatusLedIsOnWhileTheTickRunsAndBlinksAt2HzWhileNfaultIsLow) {
  const std::uint32_t bsrr = gpio::BsrrA::reg.address();
  const std::uint32_t on = 1u << 5, off = 1u << (16 + 5);
  EXPECT_EQ(hw.count_writes(bsrr, on), 0u) << "off until the tick runs";
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  tick_at(25);
  EXPECT_EQ(hw.count_writes(bsrr, on), 1u);
  for (std::uint64_t t = 75; t < 1'000'000; t += 50) tick_at(t);
  EXPECT_EQ(hw.count_writes(bsrr, on), 1u) << "steady";
  EXPECT_EQ(hw.count_writes(bsrr, off), 0u);

  hw.poke(gpio::IdrC::reg, 0);  // nFAULT asserted from t = 1 s
  const std::size_t from = hw.log_size();
  for (std::uint64_t t = 1'000'025; t < 2'000'000; t += 50) tick_at(t);
  // 1.00 .. 2.00 s: on at 1.00, off at 1.25, on at 1.50, off at 1.75 (250 ms phases).
  EXPECT_EQ(hw.count_writes(bsrr, off, from), 2u);
  EXPECT_EQ(hw.count_writes(bsrr, on, from), 1u);
}

}  // namespace
}  // namespace palp::stm32::board_test
