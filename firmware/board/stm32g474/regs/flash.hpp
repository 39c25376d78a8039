// SPDX-License-Identifier: Apache-2.0
// FLASH controller. Base: stm32g474-facts.md §2 / §1.2; offsets and fields: §1.2 (ACR, KEYR, SR,
// CR), §1.3 (OPTR); ECCR's fields are not in the facts sheet: they are ST's SVD's (the SVD
// cross-check in tests/stm32 holds every field here to it), their meaning noted per field.
// Field names are the SVD's where the facts sheet spells them otherwise (CR.START = "STRT",
// SR.MISSERR = "MISERR" in §1.2).
#pragma once

#include "register.hpp"

namespace palp::stm32::flash {

inline constexpr std::uint32_t kBase = 0x4002'2000;  // facts §2, §1.2

struct Acr {  // facts §1.2 FLASH_ACR (0x00)
  static constexpr Field LATENCY{"LATENCY", 0, 4};  // wait states
  static constexpr Field PRFTEN{"PRFTEN", 8, 1};
  static constexpr Field ICEN{"ICEN", 9, 1};
  static constexpr Field DCEN{"DCEN", 10, 1};
  static constexpr Field ICRST{"ICRST", 11, 1};  // instruction cache reset (while ICEN = 0)
  static constexpr Field DCRST{"DCRST", 12, 1};  // data cache reset (while DCEN = 0)
  static constexpr Field fields[] = {LATENCY, PRFTEN, ICEN, DCEN, ICRST, DCRST};
  static constexpr Register reg{"FLASH", "FLASH_ACR", kBase, 0x00, fields};
};

struct Keyr {  // facts §1.2 FLASH_KEYR (0x08): KEY1 then KEY2 clears CR.LOCK
  static constexpr Field KEYR{"KEYR", 0, 32};
  static constexpr std::uint32_t kKey1 = 0x4567'0123;  // facts §1.2 (HAL FLASH_KEY1)
  static constexpr std::uint32_t kKey2 = 0xCDEF'89AB;  // facts §1.2 (HAL FLASH_KEY2)
  static constexpr Field fields[] = {KEYR};
  static constexpr Register reg{"FLASH", "FLASH_KEYR", kBase, 0x08, fields};
};

struct Sr {  // facts §1.2 FLASH_SR (0x10); flags cleared by writing 1 (HAL __HAL_FLASH_CLEAR_FLAG)
  static constexpr Field EOP{"EOP", 0, 1};
  static constexpr Field OPERR{"OPERR", 1, 1};
  static constexpr Field PROGERR{"PROGERR", 3, 1};  // the double word was not erased
  static constexpr Field WRPERR{"WRPERR", 4, 1};    // write-protected page
  static constexpr Field PGAERR{"PGAERR", 5, 1};    // alignment
  static constexpr Field SIZERR{"SIZERR", 6, 1};
  static constexpr Field PGSERR{"PGSERR", 7, 1};  // sequence (e.g. a flag left set, PG and PER)
  static constexpr Field MISSERR{"MISSERR", 8, 1};
  static constexpr Field FASTERR{"FASTERR", 9, 1};
  static constexpr Field RDERR{"RDERR", 14, 1};
  static constexpr Field OPTVERR{"OPTVERR", 15, 1};
  static constexpr Field BSY{"BSY", 16, 1};
  static constexpr Field fields[] = {EOP,    OPERR,   PROGERR, WRPERR, PGAERR, SIZERR,
                                     PGSERR, MISSERR, FASTERR, RDERR,  OPTVERR, BSY};
  static constexpr Register reg{"FLASH", "FLASH_SR", kBase, 0x10, fields};

  /// Every flag an erase or program can leave (EOP included): written back as 1s to clear them.
  static constexpr std::uint32_t kClearable =
      EOP.mask() | OPERR.mask() | PROGERR.mask() | WRPERR.mask() | PGAERR.mask() |
      SIZERR.mask() | PGSERR.mask() | MISSERR.mask() | FASTERR.mask() | RDERR.mask() |
      OPTVERR.mask();
  /// The error flags (kClearable without EOP).
  static constexpr std::uint32_t kErrors = kClearable & ~EOP.mask();
};

struct Cr {  // facts §1.2 FLASH_CR (0x14); reset value LOCK | OPTLOCK (SVD)
  static constexpr Field PG{"PG", 0, 1};     // programming (a double word)
  static constexpr Field PER{"PER", 1, 1};   // page erase
  static constexpr Field PNB{"PNB", 3, 7};   // page in the bank, 0..127
  static constexpr Field BKER{"BKER", 11, 1};  // bank of the page erase: 1 = bank 2 (DBANK = 1)
  static constexpr Field START{"START", 16, 1};  // "STRT" in facts §1.2: starts the erase
  static constexpr Field LOCK{"LOCK", 31, 1};    // set: CR write-protected until KEYR unlocks
  static constexpr Field fields[] = {PG, PER, PNB, BKER, START, LOCK};
  static constexpr Register reg{"FLASH", "FLASH_CR", kBase, 0x14, fields};
};

// FLASH_ECCR (0x18; offset facts §1.2, fields SVD). A double ECC error on a read sets ECCD and
// raises the NMI (issue 21; the NMI route is ST's, RM0440 "ECC correction", not re-read this
// session); ADDR_ECC is the failing double word's byte offset in its bank and BK_ECC the bank
// (SVD descriptions "ECC fail address", "ECC fail bank"; the offset-in-bank reading is RM0440's
// from memory: flash_ecc.hpp does not depend on it). ECCD/ECCC are cleared by writing 1 (HAL's
// __HAL_FLASH_CLEAR_FLAG sets them in ECCR; from memory, unverified here).
struct Eccr {
  static constexpr Field ADDR_ECC{"ADDR_ECC", 0, 19};
  static constexpr Field BK_ECC{"BK_ECC", 21, 1};
  static constexpr Field SYSF_ECC{"SYSF_ECC", 22, 1};  // the error was in system flash
  static constexpr Field ECCCIE{"ECCCIE", 24, 1};      // single-error (corrected) interrupt enable
  static constexpr Field ECCC{"ECCC", 30, 1};          // a single error was corrected
  static constexpr Field ECCD{"ECCD", 31, 1};          // a double error was detected (NMI)
  static constexpr Field fields[] = {ADDR_ECC, BK_ECC, SYSF_ECC, ECCCIE, ECCC, ECCD};
  static constexpr Register reg{"FLASH", "FLASH_ECCR", kBase, 0x18, fields};
};

struct Optr {  // facts §1.3 FLASH_OPTR (0x20), read only here
  static constexpr Field BFB2{"BFB2", 20, 1};    // boot from bank 2 (banks may be swapped)
  static constexpr Field DBANK{"DBANK", 22, 1};  // 1 = dual bank, 2 KB pages (factory default)
  static constexpr Field fields[] = {BFB2, DBANK};
  static constexpr Register reg{"FLASH", "FLASH_OPTR", kBase, 0x20, fields};
};

}  // namespace palp::stm32::flash
