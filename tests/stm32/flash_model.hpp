// SPDX-License-Identifier: Apache-2.0
// A host model of the STM32G474 flash controller and of the calibration pages it drives, as an
// Access for the register seam (regs/register.hpp), enforcing the part's rules
// (stm32g474-facts.md §1.2; NOTES.md "Calibration in flash"):
// - CR is locked until KEYR gets KEY1 then KEY2 (a wrong key locks it until reset); writes to a
//   locked CR are ignored and counted as rule breaks;
// - page erase: PER + BKER + PNB, then START; BSY for a few SR reads; every double word of the
//   page reads 0xFF.. afterwards (SR reads BSY 3 times for an erase, once for a program);
// - programming: PG, then the low word at an 8-aligned address, then the high word at +4; the
//   double word must be erased (else PROGERR, unchanged); a misaligned first word is PGAERR, a
//   flash write without PG or an operation started with an error flag still set is PGSERR;
// - error flags and ECCR's ECCD/ECCC are cleared by writing 1;
// - reading a double word with a double ECC error returns junk, sets ECCR.ECCD, ADDR_ECC (its
//   byte offset in the bank) and BK_ECC, and raises the NMI: calls nmi() synchronously, the way
//   the board's NMI_Handler sees it;
// - the model holds only the two calibration pages of bank 2; any access elsewhere in flash,
//   any operation started while BSY and any read of bank 2 while BSY (the real bank stalls) is
//   a rule break, counted in violations().
// Power cuts: cut_at(n, tear) makes the n-th flash operation (0-based; an erase start or a
// double-word program) end the way `tear` says and powers the part off: later writes are lost,
// SR reads BSY. power_on() resets the registers (memory kept) like a reset.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "flash_driver.hpp"

namespace palp::stm32::test {

/// How a cut operation ends.
enum class Tear : std::uint8_t {
  not_started,  // the cut came just before it: nothing changed
  ecc_error,    // torn: the double word (program) or every double word of the page (erase)
                // reads with a double ECC error
  partial,      // torn with consistent ECC: program = only some of the 0 bits written; erase =
                // every other double word erased, the rest still old (the marker included)
  completed,    // it finished, the power went right after
};

class FlashModel {
 public:
  static constexpr std::uint32_t kWords = flash::kStoragePages * flash::kPageSize / 8;
  static constexpr std::uint64_t kErased = ~std::uint64_t{0};
  /// OPTR factory default (facts §1.3): DBANK = 1.
  static constexpr std::uint32_t kOptrFactory = 0xFFEF'F8AA;

  struct DoubleWord {
    std::uint64_t value = kErased;
    bool ecc_bad = false;
  };
  struct Operation {
    bool erase;  // else program
    std::uint32_t address;
  };

  /// nmi() starts routed to the board's hook (flash_driver.hpp handle_ecc_nmi with the board's
  /// log), as NMI_Handler does; an NMI the hook refuses is counted in fatal_nmis() (on the
  /// target: the default handler, a stop).
  FlashModel() {
    reset_registers();
    nmi = [this] {
      if (!flash::handle_ecc_nmi(*this, flash::ecc_fault_log())) ++fatal_nmis_;
    };
  }
  FlashModel(const FlashModel&) = delete;
  FlashModel& operator=(const FlashModel&) = delete;

  // --- Access ------------------------------------------------------------------------------
  std::uint32_t read(std::uint32_t address) {
    ++accesses_;
    if (is_flash(address)) return read_flash(address);
    if (address == flash::Sr::reg.address()) {
      if (!powered_) return flash::Sr::BSY.mask();
      if (busy_polls_ == 0) return sr_;
      if (hold_busy_) return sr_ | flash::Sr::BSY.mask();
      if (--busy_polls_ == 0) sr_ |= flash::Sr::EOP.mask();  // seen from the next read on
      return (sr_ & ~flash::Sr::EOP.mask()) | flash::Sr::BSY.mask();
    }
    if (address == flash::Cr::reg.address()) return cr_;
    if (address == flash::Eccr::reg.address()) return eccr_;
    if (address == flash::Acr::reg.address()) return acr_;
    if (address == flash::Optr::reg.address()) return optr_;
    if (address == flash::Keyr::reg.address()) return 0;
    violation("read of an unmodelled address");
    return 0;
  }

  void write(std::uint32_t address, std::uint32_t value) {
    ++accesses_;
    if (!powered_) return;
    if (is_flash(address)) return write_flash(address, value);
    if (address == flash::Keyr::reg.address()) return write_key(value);
    if (address == flash::Sr::reg.address()) {
      sr_ &= ~(value & flash::Sr::kClearable);
      return;
    }
    if (address == flash::Cr::reg.address()) return write_cr(value);
    if (address == flash::Eccr::reg.address()) {
      const std::uint32_t w1c = flash::Eccr::ECCD.mask() | flash::Eccr::ECCC.mask();
      eccr_ = (eccr_ & ~(value & w1c) & ~flash::Eccr::ECCCIE.mask()) |
              (value & flash::Eccr::ECCCIE.mask());
      return;
    }
    if (address == flash::Acr::reg.address()) {
      acr_log_.push_back(value);
      acr_ = value;
      return;
    }
    violation("write to an unmodelled address");
  }

  // --- test controls -------------------------------------------------------------------------
  std::function<void()> nmi;  // the NMI a double ECC error raises
  std::uint32_t fatal_nmis() const { return fatal_nmis_; }
  /// On: the running operation never ends (SR keeps BSY), as a hung controller would.
  void hold_busy(bool on) { hold_busy_ = on; }
  void set_boot_from_bank2(bool on) {
    optr_ = on ? optr_ | flash::Optr::BFB2.mask() : optr_ & ~flash::Optr::BFB2.mask();
  }
  void set_dual_bank(bool on) {
    optr_ = on ? optr_ | flash::Optr::DBANK.mask() : optr_ & ~flash::Optr::DBANK.mask();
  }
  /// The next erase of `page` (bank-2 page number) ends with WRPERR, the page untouched.
  void write_protect_page(std::uint32_t page) { protected_page_ = page; }
  void cut_at(std::uint32_t operation, Tear tear) {
    cut_at_ = operation;
    tear_ = tear;
  }
  bool powered() const { return powered_; }
  /// A reset after a power cut (or a plain reset): registers to their reset values, any
  /// operation gone, memory kept, the cut disarmed, the operation count from 0.
  void power_on() {
    powered_ = true;
    cut_at_ = kNever;
    reset_registers();
  }

  DoubleWord& at(std::uint32_t address) { return memory_[(address - flash::kStorageBase) / 8]; }
  const std::vector<Operation>& operations() const { return operations_; }
  const std::vector<std::string>& violations() const { return violations_; }
  const std::vector<std::uint32_t>& acr_writes() const { return acr_log_; }
  std::uint64_t accesses() const { return accesses_; }
  std::uint32_t operation_count() const { return started_; }
  std::uint32_t cr() const { return cr_; }
  std::uint32_t sr() const { return sr_; }
  std::uint32_t eccr() const { return eccr_; }
  std::uint32_t acr() const { return acr_; }
  bool busy() const { return busy_polls_ > 0; }

 private:
  static constexpr std::uint32_t kNever = ~0u;
  static constexpr std::uint32_t kEraseBusyPolls = 3;
  static constexpr std::uint32_t kProgramBusyPolls = 1;
  static constexpr std::uint32_t kAcrReset = 0x0004'0601;  // SVD FLASH_ACR reset value

  static bool is_flash(std::uint32_t address) {
    return address >= 0x0800'0000 && address < 0x0808'0000;
  }
  void violation(std::string what) { violations_.push_back(std::move(what)); }

  void reset_registers() {
    cr_ = flash::Cr::LOCK.mask() | (1u << 30);  // LOCK | OPTLOCK (SVD reset 0xC0000000)
    sr_ = 0;
    eccr_ = 0;
    acr_ = kAcrReset;
    key_stage_ = 0;
    key_failed_ = false;
    busy_polls_ = 0;
    low_pending_ = false;
    started_ = 0;
  }

  std::uint32_t read_flash(std::uint32_t address) {
    if (!flash::FlashDriver<FlashModel>::in_storage(address, 4)) {
      violation("read outside the calibration pages");
      return 0xFFFF'FFFF;
    }
    if (busy_polls_ > 0) violation("read of bank 2 while BSY");
    const DoubleWord& dw = at(address & ~7u);
    if (dw.ecc_bad) {
      eccr_ = (eccr_ & flash::Eccr::ECCCIE.mask()) | flash::Eccr::ECCD.mask() |
              flash::Eccr::BK_ECC.mask() |
              flash::Eccr::ADDR_ECC.encode((address & ~7u) - flash::kBank2Base);
      if (nmi) nmi();
      return 0xA5A5'0000u ^ address;  // junk
    }
    return static_cast<std::uint32_t>(dw.value >> ((address & 4u) ? 32 : 0));
  }

  void write_key(std::uint32_t value) {
    if (key_failed_ || (cr_ & flash::Cr::LOCK.mask()) == 0) return;
    if (key_stage_ == 0 && value == flash::Keyr::kKey1) {
      key_stage_ = 1;
    } else if (key_stage_ == 1 && value == flash::Keyr::kKey2) {
      cr_ &= ~flash::Cr::LOCK.mask();
      key_stage_ = 0;
    } else {
      key_failed_ = true;  // locked until reset
      violation("wrong KEYR sequence");
    }
  }

  void write_cr(std::uint32_t value) {
    if (cr_ & flash::Cr::LOCK.mask()) {
      violation("write to a locked FLASH_CR");
      return;
    }
    if (busy_polls_ > 0) violation("FLASH_CR written while BSY");
    const bool start = flash::Cr::START.decode(value) == 1 && flash::Cr::START.decode(cr_) == 0;
    cr_ = value & ~flash::Cr::START.mask();
    if (!start) return;
    if (flash::Cr::PER.decode(value) == 0 || flash::Cr::PG.decode(value) == 1) {
      sr_ |= flash::Sr::PGSERR.mask();
      violation("START without PER alone");
      return;
    }
    if (sr_ & flash::Sr::kErrors) {
      sr_ |= flash::Sr::PGSERR.mask();
      return;
    }
    const std::uint32_t page = flash::Cr::PNB.decode(value);
    const std::uint32_t address = flash::kBank2Base + page * flash::kPageSize;
    if (flash::Cr::BKER.decode(value) != 1 ||
        !flash::FlashDriver<FlashModel>::in_storage(address, 8)) {
      violation("erase outside the calibration pages");
      return;
    }
    operations_.push_back({true, address});
    if (page == protected_page_) {
      sr_ |= flash::Sr::WRPERR.mask();
      return;
    }
    busy_polls_ = kEraseBusyPolls;
    if (cut(address, true)) return;
    for (std::uint32_t k = 0; k < flash::kPageSize; k += 8) at(address + k) = DoubleWord{};
  }

  void write_flash(std::uint32_t address, std::uint32_t value) {
    if (!flash::FlashDriver<FlashModel>::in_storage(address, 4)) {
      violation("write outside the calibration pages");
      return;
    }
    if (flash::Cr::PG.decode(cr_) == 0 || busy_polls_ > 0) {
      sr_ |= flash::Sr::PGSERR.mask();
      violation("flash written without PG or while BSY");
      return;
    }
    if (!low_pending_) {
      if (address % 8 != 0) {
        sr_ |= flash::Sr::PGAERR.mask();
        return;
      }
      low_pending_ = true;
      low_address_ = address;
      low_value_ = value;
      return;
    }
    low_pending_ = false;
    if (address != low_address_ + 4) {
      sr_ |= flash::Sr::PGSERR.mask();
      return;
    }
    if (sr_ & flash::Sr::kErrors) {
      sr_ |= flash::Sr::PGSERR.mask();
      return;
    }
    operations_.push_back({false, low_address_});
    DoubleWord& dw = at(low_address_);
    if (dw.ecc_bad || dw.value != kErased) {
      sr_ |= flash::Sr::PROGERR.mask();
      return;
    }
    busy_polls_ = kProgramBusyPolls;
    const std::uint64_t target = std::uint64_t{low_value_} | std::uint64_t{value} << 32;
    if (cut(low_address_, false, target)) return;
    dw.value = target;
  }

  // The cut, if this is the operation: applies the tear and powers off. True when cut.
  bool cut(std::uint32_t address, bool erase, std::uint64_t target = 0) {
    if (started_++ != cut_at_) return false;
    powered_ = false;
    if (erase) {
      for (std::uint32_t k = 0; k < flash::kPageSize; k += 8) {
        DoubleWord& dw = at(address + k);
        if (tear_ == Tear::ecc_error) dw.ecc_bad = true;
        if (tear_ == Tear::completed || (tear_ == Tear::partial && (k / 8) % 2 == 0))
          dw = DoubleWord{};
      }
    } else {
      DoubleWord& dw = at(address);
      if (tear_ == Tear::ecc_error) dw.ecc_bad = true;
      if (tear_ == Tear::completed) dw.value = target;
      // some of the bits that should become 0 did: the ones in every other nibble
      if (tear_ == Tear::partial) dw.value = ~(~target & 0x0F0F'0F0F'0F0F'0F0Full);
    }
    return true;
  }

  std::array<DoubleWord, kWords> memory_{};
  std::vector<Operation> operations_;
  std::vector<std::string> violations_;
  std::vector<std::uint32_t> acr_log_;
  std::uint64_t accesses_ = 0;
  std::uint32_t cr_ = 0, sr_ = 0, eccr_ = 0, acr_ = 0, optr_ = kOptrFactory;
  std::uint32_t key_stage_ = 0;
  bool key_failed_ = false;
  std::uint32_t busy_polls_ = 0;
  bool low_pending_ = false;
  std::uint32_t low_address_ = 0, low_value_ = 0;
  std::uint32_t started_ = 0;
  std::uint32_t cut_at_ = kNever;
  Tear tear_ = Tear::completed;
  std::uint32_t protected_page_ = kNever;
  bool powered_ = true;
  bool hold_busy_ = false;
  std::uint32_t fatal_nmis_ = 0;
};

static_assert(RegisterAccess<FlashModel>);

}  // namespace palp::stm32::test
