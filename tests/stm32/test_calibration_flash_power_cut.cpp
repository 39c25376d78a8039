// SPDX-License-Identifier: Apache-2.0
// Power cuts at every single step of a calibration commit (issue 21): from each starting state
// (blank; A valid; A and B valid with B newest; with A newest), the power goes at each flash
// operation (the erase, each of the 30 double-word programs) in each way it can end (not
// started, torn with an ECC double error, torn with consistent ECC, completed); after the cut a
// reset and a fresh store must read exactly the old block (blank for a blank start) or, only when
// the commit marker was completely programmed, the new one. The torn slot must say it was an
// interrupted commit (erased / uncommitted / ecc_fault), never corruption, the ECC errors must
// come through the NMI hook without a fatal NMI, and the next commit must succeed.
#include <gtest/gtest.h>

#include <string>

#include "calibration_flash_support.hpp"

namespace palp::stm32::test {
namespace {

using fw::SlotStatus;

constexpr Tear kTears[] = {Tear::not_started, Tear::ecc_error, Tear::partial, Tear::completed};

const char* tear_name(Tear t) {
  switch (t) {
    case Tear::not_started: return "not_started";
    case Tear::ecc_error: return "ecc_error";
    case Tear::partial: return "partial";
    case Tear::completed: return "completed";
  }
  return "?";
}

/// The block the part held before the commit under test, after `commits` earlier commits.
std::vector<std::uint8_t> old_block(int commits) {
  return commits == 0 ? erased_read() : calibration_bytes(commits);
}

/// Starts a commit of `block` with the power cut at operation `op`, polls until the power is
/// gone. False if the commit ended before the cut (it must not).
bool commit_cut_at(FlashModel& model, const std::vector<std::uint8_t>& block, std::uint32_t op,
                   Tear tear) {
  model.power_on();
  model.cut_at(op, tear);
  CalibrationStore store(model);
  if (!store.begin_write(block.data(), block.size())) return !model.powered();
  for (int polls = 0; model.powered() && polls < 10'000; ++polls) {
    const fw::CommitState s = store.poll();
    if (s == fw::CommitState::done || s == fw::CommitState::failed) return false;
  }
  return !model.powered();
}

constexpr std::uint32_t kOperations = 31;  // 1 erase + 30 double words for a 208-byte block

TEST(Stm32CalibrationFlashPowerCut, EveryStepOfACommitLeavesExactlyTheOldOrTheNewBlock) {
  const std::vector<std::uint8_t> fresh = calibration_bytes(100);
  ASSERT_EQ(CalibrationStore::Journal::operations_for(fresh.size()), kOperations);
  int ecc_scans = 0;
  for (int commits = 0; commits <= 3; ++commits) {
    // the slot the commit writes: A when blank or B is newest, B when A is newest
    const std::size_t target = commits % 2 == 1 ? 1 : 0;
    for (std::uint32_t op = 0; op < kOperations; ++op) {
      for (Tear tear : kTears) {
        SCOPED_TRACE(std::to_string(commits) + " earlier commits, cut at operation " +
                     std::to_string(op) + ", " + tear_name(tear));
        FlashModel model;
        for (int n = 1; n <= commits; ++n) ASSERT_TRUE(commit(model, calibration_bytes(n)));
        ASSERT_TRUE(commit_cut_at(model, fresh, op, tear));

        const Boot b = boot(model);
        const bool marker_written = op == kOperations - 1 && tear == Tear::completed;
        EXPECT_EQ(b.bytes, marker_written ? fresh : old_block(commits));
        const SlotStatus torn = b.scan.slots[target].status;
        if (!marker_written && op > 0) {  // the erase finished: a partly written slot
          EXPECT_TRUE(torn == SlotStatus::erased || torn == SlotStatus::uncommitted ||
                      torn == SlotStatus::ecc_fault)
              << fw::slot_status_name(torn);
        }
        if (tear == Tear::ecc_error && (op == 0 || op == 1 || op == kOperations - 1)) {
          EXPECT_EQ(torn, SlotStatus::ecc_fault);  // the scan read the torn word: via the NMI
        }
        ecc_scans += torn == SlotStatus::ecc_fault;
        EXPECT_EQ(model.fatal_nmis(), 0u);
        EXPECT_TRUE(model.violations().empty()) << model.violations().front();

        // the next commit (erasing the torn slot again, or the older one) succeeds
        ASSERT_TRUE(commit(model, calibration_bytes(200)));
        EXPECT_EQ(boot(model).bytes, calibration_bytes(200));
      }
    }
  }
  EXPECT_GE(ecc_scans, 4 * 3);
}

TEST(Stm32CalibrationFlashPowerCut, ASecondCutWhileRewritingATornSlotStillKeepsTheOldBlock) {
  const std::vector<std::uint8_t> first = calibration_bytes(100), second = calibration_bytes(101);
  for (std::uint32_t op = 0; op < kOperations; ++op) {
    SCOPED_TRACE("second cut at operation " + std::to_string(op));
    FlashModel model;
    ASSERT_TRUE(commit(model, calibration_bytes(1)));
    ASSERT_TRUE(commit(model, calibration_bytes(2)));
    ASSERT_TRUE(commit_cut_at(model, first, kOperations - 1, Tear::ecc_error));  // torn marker
    ASSERT_TRUE(commit_cut_at(model, second, op, Tear::ecc_error));
    EXPECT_EQ(boot(model).bytes, calibration_bytes(2));
    EXPECT_EQ(model.fatal_nmis(), 0u);
  }
}

}  // namespace
}  // namespace palp::stm32::test
