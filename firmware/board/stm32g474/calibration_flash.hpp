// SPDX-License-Identifier: Apache-2.0
// Calibration storage in flash (team contract 3; NOTES.md "Calibration in flash"): the core's
// calibration block in an A/B journal (palp/fw/flash_journal.hpp) on the last two pages of bank 2
// (flash_driver.hpp: slot A 0x0807_F000, slot B 0x0807_F800), never in the image's pages.
//
//   read(bytes, size)   the newest valid block's bytes (min(size, block length)), or `size`
//                       bytes of 0xFF when no slot holds a valid block (the core reads "blank");
//                       returns the bytes written. Boot: survives torn slots (ECC NMI -> slot
//                       invalid, flash_ecc_nmi.cpp).
//   write(bytes, size)  a whole journal commit: erase the older slot, program it, commit marker
//                       last, read back; true once stored. It waits for the flash: one page
//                       erase plus 30 double-word programs for the 208-byte block, ~27 ms worst
//                       case (NOTES.md); begin_write()/poll() do the same without waiting.
//                       A flash busy beyond the poll limit: false, timed_out() (still running).
//
// Needs the option bytes DBANK = 1 (dual bank) and BFB2 = 0 (no bank-2 boot), both factory
// defaults (facts §1.3): otherwise write() returns false (writable() says why) and read() still
// reads.
#pragma once

#include <cstddef>
#include <cstdint>

#include "flash_driver.hpp"
#include "palp/fw/flash_journal.hpp"

namespace palp::stm32 {

inline constexpr fw::JournalLayout kCalibrationJournalLayout{
    {flash::kStorageBase, flash::kStorageBase + flash::kPageSize}};

template <RegisterAccess A>
class CalibrationFlash {
 public:
  using Driver = flash::FlashDriver<A>;
  using Journal = fw::FlashJournal<Driver, flash::kPageSize>;

  /// write()'s default bound on polls: 2^24 SR reads (each at least one bus access) is far
  /// beyond the ~27 ms a commit takes, so only a flash that never clears BSY reaches it.
  static constexpr std::uint32_t kPollLimit = 1u << 24;

  explicit CalibrationFlash(A& io, std::uint32_t poll_limit = kPollLimit)
      : driver_(io), journal_(driver_, kCalibrationJournalLayout), poll_limit_(poll_limit) {}

  // --- contract 3 --------------------------------------------------------------------------
  /// A commit begun with begin_write() is finished first; if its flash stays busy beyond the
  /// poll limit, 0 (nothing read, timed_out()).
  std::size_t read(std::uint8_t* bytes, std::size_t size) {
    finish();
    return journal_.read(bytes, size);
  }
  bool write(const std::uint8_t* bytes, std::size_t size) {
    return journal_.begin_commit(bytes, size) && finish();
  }

  // --- beyond the contract -----------------------------------------------------------------
  /// The same commit as write(), started only: call poll() from the main loop until it is
  /// done or failed (each call at most one flash step, never waiting on the flash).
  bool begin_write(const std::uint8_t* bytes, std::size_t size) {
    return journal_.begin_commit(bytes, size);
  }
  fw::CommitState poll() { return journal_.poll(); }
  /// Both slots' status at the last read()/commit (why a slot is not used).
  const fw::JournalScan& last_scan() const { return journal_.last_scan(); }
  fw::CommitError commit_error() const { return journal_.commit_error(); }
  fw::FlashStatus flash_status() const { return journal_.flash_status(); }
  bool writable() const { return driver_.writable(); }
  /// write()/read() gave up on a commit whose flash stayed busy (it is still running).
  bool timed_out() const { return timed_out_; }
  std::uint32_t last_error_flags() const { return driver_.last_error_flags(); }

 private:
  // Polls a running commit to its end; true when it is done (stored and read back).
  bool finish() {
    timed_out_ = false;
    for (std::uint32_t n = 0; journal_.active(); ++n) {
      if (n == poll_limit_) {
        timed_out_ = true;
        return false;
      }
      journal_.poll();
    }
    return journal_.state() == fw::CommitState::done;
  }

  Driver driver_;
  Journal journal_;
  std::uint32_t poll_limit_;
  bool timed_out_ = false;
};

}  // namespace palp::stm32
