// SPDX-License-Identifier: Apache-2.0
// The STM32G474 flash driver for calibration storage: a fw::JournalFlash
// (palp/fw/flash_journal.hpp) over the register seam, confined to the last two 2 KB pages of bank 2
// (NOTES.md "Calibration in flash"). Register facts: stm32g474-facts.md §1.1 (bank 2 at
// 0x0804_0000, 2 KB pages, 128 per bank in dual-bank mode), §1.2 (KEYR unlock, page erase
// PER/PNB/BKER/START, double-word PG, BSY, error flags, caches around an erase), §1.3 (OPTR.DBANK);
// definitions in regs/flash.hpp.
//
// Non-blocking: erase_page()/program_double_word() start the operation and return busy; poll()
// reads SR once (BSY) and, when the operation has ended, clears the flags, clears PER/PG, locks
// CR again and reports ok or failed. Nothing here waits on BSY.
//
// ECC: a torn program or erase leaves double words with a double ECC error; reading one sets
// FLASH_ECCR.ECCD and raises the NMI. read() marks the read window in an EccFaultLog, the NMI
// handler (flash_ecc_nmi.cpp: NMI_Handler -> handle_ecc_nmi) counts the fault, clears ECCD and
// returns into the read, and read() reports FlashStatus::ecc_fault. See handle_ecc_nmi.
#pragma once

#include <cstddef>
#include <cstdint>

#include "palp/fw/flash_journal.hpp"
#include "regs/flash.hpp"

namespace palp::stm32::flash {

// --- where calibration lives (facts §1.1, dual-bank mode) ----------------------------------------
inline constexpr std::uint32_t kBank2Base = 0x0804'0000;
inline constexpr std::uint32_t kPageSize = 0x800;  // 2 KB with DBANK = 1
inline constexpr std::uint32_t kPagesPerBank = 128;
/// Slot A = bank-2 page 126 (0x0807_F000), slot B = page 127 (0x0807_F800): the end of flash.
inline constexpr std::uint32_t kStorageFirstPage = 126;
inline constexpr std::uint32_t kStoragePages = 2;
inline constexpr std::uint32_t kStorageBase = kBank2Base + kStorageFirstPage * kPageSize;
inline constexpr std::uint32_t kStorageEnd = kStorageBase + kStoragePages * kPageSize;
static_assert(kStorageBase == 0x0807'F000 && kStorageEnd == 0x0808'0000);

// --- the ECC fault record the NMI handler fills --------------------------------------------------
struct EccFaultLog {
  volatile std::uint32_t faults = 0;     // flash double ECC errors taken (every one)
  volatile std::uint32_t last_eccr = 0;  // FLASH_ECCR at the last one (ADDR_ECC, BK_ECC: debug)
  volatile bool expecting = false;       // a FlashDriver::read() is running: the fault is its
};

/// The board's one log (defined in flash_ecc_nmi.cpp with the NMI handler, so using the driver
/// links the handler into the image).
EccFaultLog& ecc_fault_log();

/// The NMI hook. Returns true when the NMI was a flash double ECC error raised inside a
/// FlashDriver::read(): it has been counted and ECCD cleared, and the handler may return. It
/// returns false (the caller treats the NMI as fatal) for any other NMI, and for an ECC error
/// outside a read window (the image itself is damaged).
/// Why returning is safe: the ECC error is not a fault of the load — the load completes with
/// unusable data and the NMI is taken after it; the exception return resumes the next
/// instruction with the interrupted context restored by hardware. Clearing ECCD first stops the
/// NMI from being raised again. read() discards what it read once `faults` has moved.
template <RegisterAccess A>
bool handle_ecc_nmi(A& io, EccFaultLog& log) {
  const std::uint32_t eccr = read(io, Eccr::reg);
  if (Eccr::ECCD.decode(eccr) == 0) return false;
  log.last_eccr = eccr;
  log.faults = log.faults + 1;
  // Write 1 to ECCD only (ECCC left as it is; ECCCIE kept).
  io.write(Eccr::reg.address(), (eccr & Eccr::ECCCIE.mask()) | Eccr::ECCD.mask());
  return log.expecting;
}

/// DSB + ISB on the target: the loads are done and a pending NMI has been taken before the
/// next instruction runs (ARMv7-M: an ISB makes pending exceptions visible).
inline void ecc_barrier() {
#if defined(__arm__)
  asm volatile("dsb\n\tisb" ::: "memory");
#else
  asm volatile("" ::: "memory");
#endif
}

template <RegisterAccess A>
class FlashDriver {
 public:
  /// Reads OPTR once. Erase and program are refused (reads still work) unless DBANK = 1 and
  /// BFB2 = 0 (facts §1.3): in single-bank mode (4 KB pages, facts §1.1) the two slots would
  /// share one page; booting from bank 2 may swap the banks (SYSCFG_MEMRMP.FB_MODE, facts §1.4),
  /// and then 0x0807_F000 would no longer be the bank BKER = 1 erases.
  explicit FlashDriver(A& io, EccFaultLog& log = ecc_fault_log())
      : io_(io), log_(log), writable_(supported_banks(stm32::read(io, Optr::reg))) {}

  /// The option bytes allow writing: dual bank, no bank-2 boot.
  bool writable() const { return writable_; }
  /// SR's error flags at the end of the last failed operation (0: none).
  std::uint32_t last_error_flags() const { return last_errors_; }

  static constexpr bool in_storage(std::uint32_t address, std::size_t size) {
    return address >= kStorageBase && address < kStorageEnd && size <= kStorageEnd - address;
  }

  /// `size` bytes at `address` (both multiples of 8, inside the storage): ok, ecc_fault (a
  /// double ECC error during the read: the bytes are meaningless), busy (an operation runs:
  /// bank 2 is stalled) or refused.
  fw::FlashStatus read(std::uint32_t address, std::uint8_t* bytes, std::size_t size) {
    if (address % 8 != 0 || size % 8 != 0 || !in_storage(address, size))
      return fw::FlashStatus::refused;
    if (op_ != Op::none) return fw::FlashStatus::busy;
    const std::uint32_t before = log_.faults;
    log_.expecting = true;
    for (std::size_t k = 0; k < size; k += 4) {
      const std::uint32_t word = io_.read(address + static_cast<std::uint32_t>(k));
      for (std::size_t b = 0; b < 4; ++b) bytes[k + b] = static_cast<std::uint8_t>(word >> (8 * b));
    }
    ecc_barrier();
    log_.expecting = false;
    if (log_.faults == before) return fw::FlashStatus::ok;
    reset_data_cache();  // a line holding the torn word must not be served again from the cache
    return fw::FlashStatus::ecc_fault;
  }

  /// Starts erasing the page holding `address` (facts §1.2: BKER = 1 for bank 2, PNB, PER,
  /// START); the data cache is off until it ends. busy = started.
  fw::FlashStatus erase_page(std::uint32_t address) {
    const fw::FlashStatus ready = prepare(address, 1);
    if (ready != fw::FlashStatus::ok) return ready;
    data_cache_was_on_ = read_field(io_, Acr::reg, Acr::DCEN) == 1;
    if (data_cache_was_on_) write_field(io_, Acr::reg, Acr::DCEN, 0);
    const std::uint32_t page = (address - kBank2Base) / kPageSize;
    const std::uint32_t cr = stm32::read(io_, Cr::reg) & ~kOperationBits;
    io_.write(Cr::reg.address(), cr | Cr::PER.mask() | Cr::BKER.mask() | Cr::PNB.encode(page));
    io_.write(Cr::reg.address(),
              cr | Cr::PER.mask() | Cr::BKER.mask() | Cr::PNB.encode(page) | Cr::START.mask());
    op_ = Op::erase;
    return fw::FlashStatus::busy;
  }

  /// Starts programming the double word at `address` (8-aligned, erased): PG, then the low
  /// word, then the high word (facts §1.2). busy = started.
  fw::FlashStatus program_double_word(std::uint32_t address, std::uint64_t value) {
    if (address % 8 != 0) return fw::FlashStatus::refused;
    const fw::FlashStatus ready = prepare(address, 8);
    if (ready != fw::FlashStatus::ok) return ready;
    const std::uint32_t cr = stm32::read(io_, Cr::reg) & ~kOperationBits;
    io_.write(Cr::reg.address(), cr | Cr::PG.mask());
    io_.write(address, static_cast<std::uint32_t>(value));
    ecc_barrier();  // HAL: an ISB between the two words
    io_.write(address + 4, static_cast<std::uint32_t>(value >> 32));
    op_ = Op::program;
    return fw::FlashStatus::busy;
  }

  /// busy while BSY; then once the operation's end (ok / failed), with flags cleared, PG/PER
  /// cleared, CR locked and (after an erase) the caches flushed and re-enabled; ok when idle.
  fw::FlashStatus poll() {
    if (op_ == Op::none) return fw::FlashStatus::ok;
    const std::uint32_t sr = stm32::read(io_, Sr::reg);
    if (Sr::BSY.decode(sr) == 1) return fw::FlashStatus::busy;
    const std::uint32_t errors = sr & Sr::kErrors;
    io_.write(Sr::reg.address(), sr & Sr::kClearable);
    io_.write(Cr::reg.address(), (stm32::read(io_, Cr::reg) & ~kOperationBits) | Cr::LOCK.mask());
    if (op_ == Op::erase) flush_caches();
    op_ = Op::none;
    last_errors_ = errors;
    return errors == 0 ? fw::FlashStatus::ok : fw::FlashStatus::failed;
  }

 private:
  enum class Op : std::uint8_t { none, erase, program };
  static constexpr bool supported_banks(std::uint32_t optr) {
    return Optr::DBANK.decode(optr) == 1 && Optr::BFB2.decode(optr) == 0;
  }
  static constexpr std::uint32_t kOperationBits =
      Cr::PG.mask() | Cr::PER.mask() | Cr::PNB.mask() | Cr::BKER.mask() | Cr::START.mask();

  // Common checks before an operation, then unlock and clear old flags (a flag left set makes
  // the next operation fail with PGSERR; HAL clears them the same way).
  fw::FlashStatus prepare(std::uint32_t address, std::size_t size) {
    if (!writable_ || !in_storage(address, size)) return fw::FlashStatus::refused;
    if (op_ != Op::none || Sr::BSY.decode(stm32::read(io_, Sr::reg)) == 1)
      return fw::FlashStatus::refused;
    if (read_field(io_, Cr::reg, Cr::LOCK) == 1) {
      io_.write(Keyr::reg.address(), Keyr::kKey1);
      io_.write(Keyr::reg.address(), Keyr::kKey2);
      if (read_field(io_, Cr::reg, Cr::LOCK) == 1) return fw::FlashStatus::locked;
    }
    io_.write(Sr::reg.address(), Sr::kClearable);
    return fw::FlashStatus::ok;
  }

  void reset_data_cache() {
    const bool on = read_field(io_, Acr::reg, Acr::DCEN) == 1;
    if (on) write_field(io_, Acr::reg, Acr::DCEN, 0);
    write_field(io_, Acr::reg, Acr::DCRST, 1);
    write_field(io_, Acr::reg, Acr::DCRST, 0);
    if (on) write_field(io_, Acr::reg, Acr::DCEN, 1);
  }

  // After an erase, as HAL's FLASH_FlushCaches (facts §1.2): the instruction cache disabled,
  // reset and re-enabled if it was on; the data cache (off since the erase began) reset and
  // re-enabled if it was on.
  void flush_caches() {
    if (read_field(io_, Acr::reg, Acr::ICEN) == 1) {
      write_field(io_, Acr::reg, Acr::ICEN, 0);
      write_field(io_, Acr::reg, Acr::ICRST, 1);
      write_field(io_, Acr::reg, Acr::ICRST, 0);
      write_field(io_, Acr::reg, Acr::ICEN, 1);
    }
    if (data_cache_was_on_) {
      write_field(io_, Acr::reg, Acr::DCRST, 1);
      write_field(io_, Acr::reg, Acr::DCRST, 0);
      write_field(io_, Acr::reg, Acr::DCEN, 1);
    }
  }

  A& io_;
  EccFaultLog& log_;
  bool writable_;
  bool data_cache_was_on_ = false;
  Op op_ = Op::none;
  std::uint32_t last_errors_ = 0;
};

}  // namespace palp::stm32::flash
