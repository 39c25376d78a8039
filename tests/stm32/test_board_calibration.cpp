// SPDX-License-Identifier: Apache-2.0
// The STM32G474 board's calibration storage (stm_board.hpp write_calibration / idle / read_calibration)
// on the flash model (flash_model.hpp, the part's rules): a commit runs over main-loop passes, each
// starting at most one flash operation and never waiting for BSY, idle() does not sleep while it
// runs, and a reboot (a fresh board on the same flash) reads the block.
#include <cstdint>
#include <string>
#include <vector>

#include "board_fixture.hpp"
#include "calibration_flash_support.hpp"

namespace palp::stm32::board_test {
namespace {

class StmBoardCalibration : public BoardTest {
 protected:
  static bool no_work(void*) { return false; }

  struct Passes {
    int passes = 0;
    std::uint32_t most_operations_started = 0;  // in one pass
    std::uint64_t most_flash_accesses = 0;      // in one pass
    int sleeps = 0;                             // WFIs in passes the commit outlived
  };
  /// Main-loop passes (idle() with nothing else to do) until the commit ends, with a tick
  /// between passes; at most `limit` passes.
  Passes run_commit(int limit = 1000) {
    Passes p;
    std::uint64_t t = 25;
    while (board.calibration_busy() && p.passes < limit) {
      const std::uint32_t ops = hw.flash_model.operation_count();
      const std::uint64_t accesses = hw.flash_model.accesses();
      cpu.events.clear();
      board.idle(&StmBoardCalibration::no_work, nullptr);
      tick_at(t += 50);
      ++p.passes;
      p.most_operations_started =
          std::max(p.most_operations_started, hw.flash_model.operation_count() - ops);
      p.most_flash_accesses = std::max(p.most_flash_accesses, hw.flash_model.accesses() - accesses);
      if (board.calibration_busy()) {
        for (const std::string& e : cpu.events) p.sleeps += e.rfind("wfi", 0) == 0;
      }
    }
    return p;
  }

  /// A reset and a fresh board on the same hardware: what its boot reads (the App's 2 KB buffer).
  std::vector<std::uint8_t> reboot_and_read() {
    hw.flash_model.power_on();
    Board::Link fresh_link(hw);
    Board fresh(hw, cpu, fresh_link, platform());
    fresh.init();
    std::vector<std::uint8_t> buffer(fw::kCalibrationMaxBlockSize);
    buffer.resize(fresh.read_calibration(buffer.data(), buffer.size()));
    return buffer;
  }
};

TEST_F(StmBoardCalibration, ACommitRunsOverBoundedMainLoopPassesWithoutSleepingAndARebootReadsIt) {
  ASSERT_TRUE(board.start_tick(20'000, handler()));
  const std::vector<std::uint8_t> block = test::calibration_bytes(1);
  ASSERT_TRUE(board.write_calibration(block.data(), block.size()));
  EXPECT_EQ(hw.flash_model.operation_count(), 1u) << "the erase started, nothing waited for";
  EXPECT_TRUE(board.calibration_busy());

  const std::size_t from = hw.log_size();
  const Passes p = run_commit();
  EXPECT_EQ(board.calibration_commit(), fw::CommitState::done);
  // One erase + 27 double words of the 208-byte block + CRC + marker: each needs its own pass.
  const auto operations = static_cast<int>(test::CalibrationStore::Journal::operations_for(block.size()));
  EXPECT_EQ(static_cast<int>(hw.flash_model.operations().size()), operations);
  EXPECT_GE(p.passes, operations) << "one flash operation per pass at most";
  EXPECT_LE(p.most_operations_started, 1u);
  // The largest pass is the last: the slot read back (~60 words) after the marker's program.
  EXPECT_LE(p.most_flash_accesses, 120u);
  EXPECT_EQ(p.sleeps, 0) << "idle() must keep polling the flash while the commit runs";
  EXPECT_TRUE(hw.flash_model.violations().empty())
      << hw.flash_model.violations().front() << " (the part's rules)";
  // The tick ran between the passes and the watchdog rule held throughout.
  EXPECT_EQ(hw.count_writes(iwdg::Kr::reg.address(), iwdg::Kr::kReload, from),
            static_cast<std::size_t>(p.passes));

  cpu.events.clear();
  board.idle(&StmBoardCalibration::no_work, nullptr);
  EXPECT_EQ(cpu.events, (std::vector<std::string>{"cpsid", "wfi (masked)", "cpsie"}))
      << "once stored, idle() sleeps again";

  EXPECT_EQ(reboot_and_read(), block);
}

TEST_F(StmBoardCalibration, ABlockWrittenWhileACommitRunsIsCommittedNextAndTheRebootReadsIt) {
  const std::vector<std::uint8_t> first = test::calibration_bytes(1);
  const std::vector<std::uint8_t> second = test::calibration_bytes(2);
  ASSERT_TRUE(board.write_calibration(first.data(), first.size()));
  board.idle(&StmBoardCalibration::no_work, nullptr);
  ASSERT_TRUE(board.write_calibration(second.data(), second.size())) << "kept, not refused";
  const Passes p = run_commit();
  EXPECT_EQ(board.calibration_commit(), fw::CommitState::done);
  EXPECT_EQ(board.calibration_failures(), 0u);
  const auto per_commit = test::CalibrationStore::Journal::operations_for(first.size());
  EXPECT_EQ(hw.flash_model.operations().size(), 2 * per_commit) << "both blocks were committed";
  EXPECT_LE(p.most_operations_started, 1u);
  EXPECT_EQ(reboot_and_read(), second);
}

TEST_F(StmBoardCalibration, EnterBootloaderFinishesARunningCommitBeforeTheReset) {
  const std::vector<std::uint8_t> block = test::calibration_bytes(3);
  ASSERT_TRUE(board.write_calibration(block.data(), block.size()));
  const std::size_t from = hw.log_size();
  board.enter_bootloader();
  EXPECT_EQ(board.calibration_commit(), fw::CommitState::done);
  EXPECT_EQ(hw.count_writes(0xE000'ED0Cu, 0x05FA'0004u, from), 1u);  // AIRCR, after the commit
  EXPECT_EQ(reboot_and_read(), block);
}

TEST_F(StmBoardCalibration, AFailedFlashOperationEndsTheCommitFailedAndTheOldBlockStays) {
  const std::vector<std::uint8_t> old_block = test::calibration_bytes(4);
  ASSERT_TRUE(board.write_calibration(old_block.data(), old_block.size()));
  run_commit();
  ASSERT_EQ(board.calibration_commit(), fw::CommitState::done);
  // The next commit erases the other page (slot B = page 127): make that erase fail (WRPERR).
  hw.flash_model.write_protect_page(127);
  const std::vector<std::uint8_t> new_block = test::calibration_bytes(5);
  ASSERT_TRUE(board.write_calibration(new_block.data(), new_block.size()));
  run_commit();
  EXPECT_EQ(board.calibration_commit(), fw::CommitState::failed);
  EXPECT_EQ(board.calibration_failures(), 1u);
  EXPECT_EQ(reboot_and_read(), old_block);
}

TEST_F(StmBoardCalibration, AReadWhileCommitsRunFinishesThemAndReadsTheNewestBlock) {
  const std::vector<std::uint8_t> first = test::calibration_bytes(6);
  const std::vector<std::uint8_t> second = test::calibration_bytes(7);
  ASSERT_TRUE(board.write_calibration(first.data(), first.size()));
  ASSERT_TRUE(board.write_calibration(second.data(), second.size()));  // waits behind the first
  std::vector<std::uint8_t> read(second.size());
  EXPECT_EQ(board.read_calibration(read.data(), read.size()), second.size());
  EXPECT_EQ(read, second);
  EXPECT_FALSE(board.calibration_busy());
}

TEST_F(StmBoardCalibration, ABootWithNothingStoredReadsErasedFlashAsBlank) {
  EXPECT_EQ(reboot_and_read(), test::erased_read());
}

}  // namespace
}  // namespace palp::stm32::board_test
