// SPDX-License-Identifier: Apache-2.0
// A two-slot (A/B) journal in flash for one small block (the calibration block, calibration.hpp):
// a power loss at any step of a commit leaves the old or the new block readable, never neither.
// Board-independent: it runs over any JournalFlash (below); the STM32G474's is
// firmware/board/stm32g474/flash_driver.hpp, the host tests' a flash model with power cuts.
//
// Each slot is one erase page of its own (slot_size bytes, a multiple of 8), all little-endian:
//     0  u32 magic 0x4C4E4A50 ("PJNL")   4 u16 journal layout (1)   6 u16 length (payload bytes)
//     8  u32 sequence (1, 2, ...)       12 u32 reserved (0)
//    16  the payload (length bytes), padded with 0xFF to a multiple of 8
//    16 + pad8(length): u32 CRC-32/ISO-HDLC of bytes [0, 16 + length), u32 0
//    slot_size - 8: u64 commit marker kJournalCommitMarker
// A commit erases the slot that does NOT hold the newest valid block, programs it one 64-bit
// double word at a time in address order, the commit marker last, and reads it back. Boot (scan)
// takes the valid slot with the highest sequence. A slot is valid when its marker, magic, layout,
// length and CRC all hold and none of its reads hit an ECC fault. Why each part:
// - the older slot is the one erased: the newest valid block is never touched, so until the new
//   slot is complete the newest is still there;
// - the marker last: a slot without it is an interrupted commit (`uncommitted`, benign), while a
//   slot WITH it that fails its CRC is corruption (`bad_crc`), which a cut never produces;
// - the CRC: covers header and payload, so a partly programmed or partly erased slot is never
//   taken for a block;
// - ECC faults: a torn program or erase leaves double-word(s) whose read reports ecc_fault (the
//   board turns the NMI into that status): the slot is invalid, the scan goes on.
// Sequence numbers are compared as plain u32: a flash page endures ~10^4 erases, far below 2^32.
//
// Nothing here waits (firmware/core's rule): a commit is a state machine — begin_commit() starts
// the erase, each poll() advances at most one flash operation — so a main loop commits without
// stalling; a caller that must wait (the board's synchronous write) polls it to the end itself.
// While a commit runs the slots are not read (the flash would stall or report busy): scan()
// and read() return at once (see each).
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include "palp/protocol/crc32.hpp"

namespace palp::fw {

/// The result of one flash step.
enum class FlashStatus : std::uint8_t {
  ok,         // done; read: the bytes are the flash's
  busy,       // an erase/program is running (started, or still going): poll() again
  ecc_fault,  // read: a double ECC error (torn program or erase); the bytes are meaningless
  refused,    // outside the storage, misaligned, or the part is not configured for it
  locked,     // the controller would not unlock
  failed,     // the operation ended with an error flag
};

constexpr const char* flash_status_name(FlashStatus s) {
  switch (s) {
    case FlashStatus::ok: return "ok";
    case FlashStatus::busy: return "busy";
    case FlashStatus::ecc_fault: return "ecc_fault";
    case FlashStatus::refused: return "refused";
    case FlashStatus::locked: return "locked";
    case FlashStatus::failed: return "failed";
  }
  return "?";
}

/// What the journal needs from a flash: absolute addresses, reads and programs in whole 64-bit
/// double words (address and size multiples of 8). erase_page/program_double_word start an
/// operation (busy = started; anything else = not started, with the reason); poll() is busy
/// while it runs, then reports its end (ok or failed) and is ok when nothing runs. read() while
/// an operation runs is busy (the bank is stalled).
template <class F>
concept JournalFlash = requires(F& f, std::uint32_t address, std::uint8_t* bytes, std::size_t size,
                                std::uint64_t value) {
  { f.read(address, bytes, size) } -> std::same_as<FlashStatus>;
  { f.erase_page(address) } -> std::same_as<FlashStatus>;
  { f.program_double_word(address, value) } -> std::same_as<FlashStatus>;
  { f.poll() } -> std::same_as<FlashStatus>;
};

inline constexpr std::uint32_t kJournalMagic = 0x4C4E4A50u;  // "PJNL"
inline constexpr std::uint16_t kJournalLayoutVersion = 1;
inline constexpr std::size_t kJournalHeaderSize = 16;
/// "PALPCMIT" in byte order; erased flash reads all ones, so it can never be mistaken for it.
inline constexpr std::uint64_t kJournalCommitMarker = 0x54494D43504C4150ull;

/// Why a slot is or is not valid.
enum class SlotStatus : std::uint8_t {
  valid,
  erased,           // marker and header read erased: never written (or fully erased)
  uncommitted,      // no (or a partly programmed) commit marker: an interrupted commit
  ecc_fault,        // a read hit a double ECC error: a torn program or erase
  bad_marker,       // the marker's place holds something that is not a (partial) marker
  bad_magic,        // marker present, header is not a journal header
  unknown_version,  // marker present, a journal layout this code does not know
  bad_length,       // length 0 or beyond the slot's capacity
  bad_crc,          // marker present but the CRC fails: corruption, not a power cut
  unreadable,       // the flash refused the read (busy, outside the storage)
};

constexpr const char* slot_status_name(SlotStatus s) {
  switch (s) {
    case SlotStatus::valid: return "valid";
    case SlotStatus::erased: return "erased";
    case SlotStatus::uncommitted: return "uncommitted";
    case SlotStatus::ecc_fault: return "ecc_fault";
    case SlotStatus::bad_marker: return "bad_marker";
    case SlotStatus::bad_magic: return "bad_magic";
    case SlotStatus::unknown_version: return "unknown_version";
    case SlotStatus::bad_length: return "bad_length";
    case SlotStatus::bad_crc: return "bad_crc";
    case SlotStatus::unreadable: return "unreadable";
  }
  return "?";
}

struct SlotInfo {
  SlotStatus status = SlotStatus::unreadable;
  std::uint32_t sequence = 0;  // valid slots only
  std::uint16_t length = 0;    // valid slots only
};

struct JournalScan {
  std::array<SlotInfo, 2> slots{};
  int newest = -1;  // index of the valid slot with the highest sequence; -1: none
};

enum class CommitState : std::uint8_t { idle, erasing, programming, done, failed };

/// Why the last commit failed (CommitState::failed).
enum class CommitError : std::uint8_t {
  none,
  bad_size,  // 0 bytes or more than the slot's capacity
  flash,     // an erase/program did not start or ended with an error (flash_status())
  verify,    // the slot read back is not the block written
};

/// Where the two slots are: two distinct erase pages of slot_size bytes each.
struct JournalLayout {
  std::array<std::uint32_t, 2> slot_address{};
};

template <JournalFlash F, std::size_t SlotSize>
class FlashJournal {
  static_assert(SlotSize % 8 == 0 && SlotSize >= 64, "a slot is whole double words");

 public:
  /// Largest payload: the slot less header, CRC double word and marker.
  static constexpr std::size_t kCapacity = SlotSize - kJournalHeaderSize - 16;
  FlashJournal(F& flash, JournalLayout layout) : flash_(flash), layout_(layout) {}

  /// Reads both slots and picks the newest valid one. While a commit runs: the last scan,
  /// unchanged (its target slot already marked uncommitted).
  const JournalScan& scan() {
    if (active()) return scan_;
    for (std::size_t i = 0; i < 2; ++i) scan_.slots[i] = check_slot(layout_.slot_address[i]);
    scan_.newest = newest_of(scan_);
    scanned_ = true;
    return scan_;
  }
  const JournalScan& last_scan() const { return scan_; }

  /// The newest valid block's first min(size, length) bytes; with no valid block `size` bytes
  /// of 0xFF (erased storage: the calibration reads as blank). Returns the bytes written; 0
  /// while a commit runs (nothing read: poll it to the end first).
  std::size_t read(std::uint8_t* bytes, std::size_t size) {
    if (active()) return 0;
    scan();
    if (scan_.newest >= 0) {
      const SlotInfo& slot = scan_.slots[static_cast<std::size_t>(scan_.newest)];
      const std::size_t n = size < slot.length ? size : slot.length;
      if (read_bytes(
              layout_.slot_address[static_cast<std::size_t>(scan_.newest)] + kJournalHeaderSize,
              bytes, n) == FlashStatus::ok) {
        return n;
      }
    }
    for (std::size_t k = 0; k < size; ++k) bytes[k] = 0xFF;
    return size;
  }

  /// Starts a commit of `size` bytes (copied): the older slot's erase starts now. False when a
  /// commit is already running (state() says so, nothing changes) or it could not start
  /// (state() failed, commit_error() says why).
  bool begin_commit(const std::uint8_t* bytes, std::size_t size) {
    if (active()) return false;
    if (size == 0 || size > kCapacity) {
      fail(CommitError::bad_size);
      return false;
    }
    if (!scanned_) scan();
    for (std::size_t k = 0; k < size; ++k) payload_[k] = bytes[k];
    length_ = static_cast<std::uint16_t>(size);
    target_ = scan_.newest == 0 ? 1u : 0u;
    sequence_ =
        scan_.newest >= 0 ? scan_.slots[static_cast<std::size_t>(scan_.newest)].sequence + 1u : 1u;
    crc_ = block_crc();
    next_ = 0;
    error_ = CommitError::none;
    // The target stops being a block the moment its erase starts.
    scan_.slots[target_] = SlotInfo{SlotStatus::uncommitted, 0, 0};
    state_ = CommitState::erasing;
    return start(flash_.erase_page(layout_.slot_address[target_]));
  }

  /// Advances a running commit by at most one flash operation; never waits.
  CommitState poll() {
    if (!active()) return state_;
    const FlashStatus s = flash_.poll();
    if (s == FlashStatus::busy) return state_;
    if (s != FlashStatus::ok) return fail(CommitError::flash, s);
    if (state_ == CommitState::erasing) {
      state_ = CommitState::programming;
    } else {
      ++next_;
    }
    if (next_ == double_words()) return verify();
    start(flash_.program_double_word(address_of(next_), double_word(next_)));
    return state_;
  }

  CommitState state() const { return state_; }
  /// A commit is running (erasing or programming): poll() it.
  bool active() const {
    return state_ == CommitState::erasing || state_ == CommitState::programming;
  }
  CommitError commit_error() const { return error_; }
  /// The flash step's status behind CommitError::flash.
  FlashStatus flash_status() const { return flash_status_; }
  /// Flash operations (erases + programs) a commit of `size` bytes takes.
  static constexpr std::size_t operations_for(std::size_t size) {
    return 1 + double_words_for(size);
  }

 private:
  bool start(FlashStatus s) {
    if (s == FlashStatus::busy) return true;
    fail(CommitError::flash, s);
    return false;
  }
  CommitState fail(CommitError e, FlashStatus s = FlashStatus::ok) {
    error_ = e;
    flash_status_ = s;
    state_ = CommitState::failed;
    return state_;
  }
  static constexpr std::size_t pad8(std::size_t n) { return (n + 7u) & ~std::size_t{7}; }
  static constexpr std::size_t double_words_for(std::size_t size) {
    return (kJournalHeaderSize + pad8(size)) / 8 + 2;  // + CRC + marker
  }
  std::size_t double_words() const { return double_words_for(length_); }
  std::uint32_t address_of(std::size_t dw) const {
    const std::uint32_t base = layout_.slot_address[target_];
    if (dw + 1 == double_words()) return base + static_cast<std::uint32_t>(SlotSize - 8);
    return base + static_cast<std::uint32_t>(8 * dw);
  }

  static std::uint32_t le32(const std::uint8_t* p) {
    return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
           std::uint32_t{p[3]} << 24;
  }
  static std::uint64_t le64(const std::uint8_t* p) {
    return std::uint64_t{le32(p)} | std::uint64_t{le32(p + 4)} << 32;
  }
  static void put32(std::uint8_t* p, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) p[k] = static_cast<std::uint8_t>(v >> (8 * k));
  }

  std::array<std::uint8_t, kJournalHeaderSize> header() const {
    std::array<std::uint8_t, kJournalHeaderSize> h{};
    put32(h.data(), kJournalMagic);
    put32(h.data() + 4, std::uint32_t{kJournalLayoutVersion} | std::uint32_t{length_} << 16);
    put32(h.data() + 8, sequence_);
    put32(h.data() + 12, 0);
    return h;
  }
  std::uint32_t block_crc() const {
    const auto h = header();
    std::uint32_t state = proto::crc32_update(proto::kCrc32Init, h.data(), h.size());
    state = proto::crc32_update(state, payload_.data(), length_);
    return proto::crc32_final(state);
  }
  /// Double word `dw` of the slot being written, in programming order.
  std::uint64_t double_word(std::size_t dw) const {
    const std::size_t count = double_words();
    if (dw + 1 == count) return kJournalCommitMarker;
    if (dw + 2 == count) return std::uint64_t{crc_};
    std::array<std::uint8_t, 8> bytes{};
    if (dw < 2) {
      const auto h = header();
      for (std::size_t k = 0; k < 8; ++k) bytes[k] = h[8 * dw + k];
    } else {
      const std::size_t first = 8 * (dw - 2);
      for (std::size_t k = 0; k < 8; ++k)
        bytes[k] = first + k < length_ ? payload_[first + k] : std::uint8_t{0xFF};
    }
    return le64(bytes.data());
  }

  FlashStatus read_bytes(std::uint32_t address, std::uint8_t* out, std::size_t size) {
    std::array<std::uint8_t, 64> chunk{};
    for (std::size_t done = 0; done < size;) {
      const std::size_t want = pad8(size - done) < chunk.size() ? pad8(size - done) : chunk.size();
      const FlashStatus s =
          flash_.read(address + static_cast<std::uint32_t>(done), chunk.data(), want);
      if (s != FlashStatus::ok) return s;
      for (std::size_t k = 0; k < want && done + k < size; ++k) out[done + k] = chunk[k];
      done += want;
    }
    return FlashStatus::ok;
  }

  static SlotStatus read_failure(FlashStatus s) {
    return s == FlashStatus::ecc_fault ? SlotStatus::ecc_fault : SlotStatus::unreadable;
  }

  SlotInfo check_slot(std::uint32_t base) {
    std::array<std::uint8_t, 64> chunk{};
    FlashStatus s = flash_.read(base + static_cast<std::uint32_t>(SlotSize - 8), chunk.data(), 8);
    if (s != FlashStatus::ok) return {read_failure(s)};
    const std::uint64_t marker = le64(chunk.data());
    if (marker != kJournalCommitMarker) {
      if ((marker & kJournalCommitMarker) == kJournalCommitMarker && marker != ~std::uint64_t{0}) {
        return {SlotStatus::uncommitted};  // programming only clears bits: a torn marker
      }
      if (marker != ~std::uint64_t{0}) return {SlotStatus::bad_marker};
      s = flash_.read(base, chunk.data(), 8);
      if (s != FlashStatus::ok) return {read_failure(s)};
      return {le64(chunk.data()) == ~std::uint64_t{0} ? SlotStatus::erased
                                                      : SlotStatus::uncommitted};
    }
    s = flash_.read(base, chunk.data(), kJournalHeaderSize);
    if (s != FlashStatus::ok) return {read_failure(s)};
    if (le32(chunk.data()) != kJournalMagic) return {SlotStatus::bad_magic};
    const std::uint32_t word1 = le32(chunk.data() + 4);
    if ((word1 & 0xFFFFu) != kJournalLayoutVersion) return {SlotStatus::unknown_version};
    const std::size_t length = word1 >> 16;
    if (length == 0 || length > kCapacity) return {SlotStatus::bad_length};
    const std::uint32_t sequence = le32(chunk.data() + 8);
    std::uint32_t state = proto::crc32_update(proto::kCrc32Init, chunk.data(), kJournalHeaderSize);
    for (std::size_t done = 0; done < length;) {
      const std::size_t want =
          pad8(length - done) < chunk.size() ? pad8(length - done) : chunk.size();
      s = flash_.read(base + static_cast<std::uint32_t>(kJournalHeaderSize + done), chunk.data(),
                      want);
      if (s != FlashStatus::ok) return {read_failure(s)};
      const std::size_t used = length - done < want ? length - done : want;
      state = proto::crc32_update(state, chunk.data(), used);
      done += want;
    }
    s = flash_.read(base + static_cast<std::uint32_t>(kJournalHeaderSize + pad8(length)),
                    chunk.data(), 8);
    if (s != FlashStatus::ok) return {read_failure(s)};
    if (le64(chunk.data()) != std::uint64_t{proto::crc32_final(state)})
      return {SlotStatus::bad_crc};
    return {SlotStatus::valid, sequence, static_cast<std::uint16_t>(length)};
  }

  static int newest_of(const JournalScan& scan) {
    int newest = -1;
    for (int i = 0; i < 2; ++i) {
      const SlotInfo& slot = scan.slots[static_cast<std::size_t>(i)];
      if (slot.status != SlotStatus::valid) continue;
      if (newest < 0 || slot.sequence > scan.slots[static_cast<std::size_t>(newest)].sequence)
        newest = i;
    }
    return newest;
  }

  /// Reads the written slot back: it must be valid, with this commit's sequence and bytes.
  CommitState verify() {
    const SlotInfo info = check_slot(layout_.slot_address[target_]);
    if (info.status != SlotStatus::valid || info.sequence != sequence_ || info.length != length_)
      return fail(CommitError::verify);
    std::array<std::uint8_t, 64> chunk{};
    const std::uint32_t base = layout_.slot_address[target_] + kJournalHeaderSize;
    for (std::size_t done = 0; done < length_; done += chunk.size()) {
      const std::size_t n = length_ - done < chunk.size() ? length_ - done : chunk.size();
      if (read_bytes(base + static_cast<std::uint32_t>(done), chunk.data(), n) != FlashStatus::ok)
        return fail(CommitError::verify);
      for (std::size_t k = 0; k < n; ++k)
        if (chunk[k] != payload_[done + k]) return fail(CommitError::verify);
    }
    scan_.slots[target_] = info;
    scan_.newest = static_cast<int>(target_);
    state_ = CommitState::done;
    return state_;
  }

  F& flash_;
  JournalLayout layout_;
  JournalScan scan_{};
  bool scanned_ = false;
  CommitState state_ = CommitState::idle;
  CommitError error_ = CommitError::none;
  FlashStatus flash_status_ = FlashStatus::ok;
  std::array<std::uint8_t, kCapacity> payload_{};
  std::uint16_t length_ = 0;
  std::size_t target_ = 0;
  std::uint32_t sequence_ = 0;
  std::uint32_t crc_ = 0;
  std::size_t next_ = 0;
};

}  // namespace palp::fw
