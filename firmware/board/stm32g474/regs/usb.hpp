// SPDX-License-Identifier: Apache-2.0
// USB: the full-speed device peripheral ("FSDEV", 16-bit variant). Register base, PMA base and
// size: stm32g474-facts.md §5.1; register offsets, fields and write semantics: §5.2. The SVD
// calls the peripheral USB_FS_device and the cross-check (tests/stm32) pins every definition
// here but BCDR, which ST's SVD lacks (see Bcdr).
//
// Registers are 16 bits wide in 32-bit slots (§5.2) and are accessed as 32-bit words like every
// other register of the seam; only the PMA needs 16-bit accesses (usb_fsdev.hpp).
//
// Write semantics (§5.2): CTR_RX/CTR_TX in EPnR and the ISTR flags are rc_w0 (writing 0 clears,
// 1 leaves unchanged: never read-modify-write them); DTOG_RX/DTOG_TX/STAT_RX/STAT_TX toggle on
// a written 1; SETUP, ISTR.CTR/DIR/EP_ID and FNR are read-only.
#pragma once

#include "register.hpp"

namespace palp::stm32::usb {

inline constexpr std::uint32_t kBase = 0x4000'5C00;     // facts §5.1 (CMSIS USB_BASE)
inline constexpr std::uint32_t kPmaBase = 0x4000'6000;  // facts §5.1 (CMSIS USB_PMAADDR)
inline constexpr std::uint32_t kPmaSize = 1024;         // facts §5.1, bytes, 16-bit 1:1 access
inline constexpr std::uint8_t kEndpointRegisters = 8;   // facts §5.1: EP0R..EP7R

struct Epr {  // facts §5.2 EPnR at 0x00 + 4n: one endpoint number, both directions
  static constexpr Field EA{"EA", 0, 4};            // rw: the endpoint number
  static constexpr Field STAT_TX{"STAT_TX", 4, 2};  // toggle
  static constexpr Field DTOG_TX{"DTOG_TX", 6, 1};  // toggle
  static constexpr Field CTR_TX{"CTR_TX", 7, 1};    // rc_w0
  static constexpr Field EP_KIND{"EP_KIND", 8, 1};  // rw
  static constexpr Field EP_TYPE{"EP_TYPE", 9, 2};  // rw
  static constexpr Field SETUP{"SETUP", 11, 1};     // read-only
  static constexpr Field STAT_RX{"STAT_RX", 12, 2};  // toggle
  static constexpr Field DTOG_RX{"DTOG_RX", 14, 1};  // toggle
  static constexpr Field CTR_RX{"CTR_RX", 15, 1};    // rc_w0
  static constexpr Field fields[] = {EA,      STAT_TX, DTOG_TX, CTR_TX,  EP_KIND,
                                     EP_TYPE, SETUP,   STAT_RX, DTOG_RX, CTR_RX};
  static constexpr Register regs[kEndpointRegisters] = {
      {"USB_FS_device", "EP0R", kBase, 0x00, fields}, {"USB_FS_device", "EP1R", kBase, 0x04, fields},
      {"USB_FS_device", "EP2R", kBase, 0x08, fields}, {"USB_FS_device", "EP3R", kBase, 0x0C, fields},
      {"USB_FS_device", "EP4R", kBase, 0x10, fields}, {"USB_FS_device", "EP5R", kBase, 0x14, fields},
      {"USB_FS_device", "EP6R", kBase, 0x18, fields}, {"USB_FS_device", "EP7R", kBase, 0x1C, fields}};

  static constexpr std::uint32_t address(std::uint8_t n) { return kBase + 4u * n; }

  // STAT_RX / STAT_TX codes (§5.2).
  static constexpr std::uint32_t kStatDisabled = 0b00;
  static constexpr std::uint32_t kStatStall = 0b01;
  static constexpr std::uint32_t kStatNak = 0b10;
  static constexpr std::uint32_t kStatValid = 0b11;
  // EP_TYPE codes (§5.2).
  static constexpr std::uint32_t kTypeBulk = 0b00;
  static constexpr std::uint32_t kTypeControl = 0b01;
  static constexpr std::uint32_t kTypeIso = 0b10;
  static constexpr std::uint32_t kTypeInterrupt = 0b11;
  /// The bits a write carries through unchanged (§5.2 "safe write recipe", mask 0x8F8F:
  /// CTR_RX | SETUP | EP_TYPE | EP_KIND | CTR_TX | EA); the toggle bits are outside it.
  static constexpr std::uint32_t kKeepMask = 0x8F8F;
};

struct Cntr {  // facts §5.2 CNTR (0x40); resets with FRES | PDWN (§5.3 item 1)
  static constexpr Field FRES{"FRES", 0, 1};
  static constexpr Field PDWN{"PDWN", 1, 1};
  static constexpr Field LP_MODE{"LP_MODE", 2, 1};
  static constexpr Field FSUSP{"FSUSP", 3, 1};
  static constexpr Field RESUME{"RESUME", 4, 1};
  static constexpr Field ESOFM{"ESOFM", 8, 1};
  static constexpr Field SOFM{"SOFM", 9, 1};
  static constexpr Field RESETM{"RESETM", 10, 1};
  static constexpr Field SUSPM{"SUSPM", 11, 1};
  static constexpr Field WKUPM{"WKUPM", 12, 1};
  static constexpr Field ERRM{"ERRM", 13, 1};
  static constexpr Field PMAOVRM{"PMAOVRM", 14, 1};
  static constexpr Field CTRM{"CTRM", 15, 1};
  static constexpr Field fields[] = {FRES,  PDWN,   LP_MODE, FSUSP, RESUME,  ESOFM, SOFM,
                                     RESETM, SUSPM, WKUPM,   ERRM,  PMAOVRM, CTRM};
  static constexpr Register reg{"USB_FS_device", "CNTR", kBase, 0x40, fields};
};

struct Istr {  // facts §5.2 ISTR (0x44): flags rc_w0 (ISTR = ~FLAG), CTR/DIR/EP_ID read-only
  static constexpr Field EP_ID{"EP_ID", 0, 4};
  static constexpr Field DIR{"DIR", 4, 1};
  static constexpr Field ESOF{"ESOF", 8, 1};
  static constexpr Field SOF{"SOF", 9, 1};
  static constexpr Field RESET{"RESET", 10, 1};
  static constexpr Field SUSP{"SUSP", 11, 1};
  static constexpr Field WKUP{"WKUP", 12, 1};
  static constexpr Field ERR{"ERR", 13, 1};
  static constexpr Field PMAOVR{"PMAOVR", 14, 1};
  static constexpr Field CTR{"CTR", 15, 1};
  static constexpr Field fields[] = {EP_ID, DIR, ESOF, SOF, RESET, SUSP, WKUP, ERR, PMAOVR, CTR};
  static constexpr Register reg{"USB_FS_device", "ISTR", kBase, 0x44, fields};
};

struct Fnr {  // facts §5.2 FNR (0x48), read-only: the frame number of the last SOF
  static constexpr Field FN{"FN", 0, 11};
  static constexpr Field LSOF{"LSOF", 11, 2};
  static constexpr Field LCK{"LCK", 13, 1};
  static constexpr Field RXDM{"RXDM", 14, 1};
  static constexpr Field RXDP{"RXDP", 15, 1};
  static constexpr Field fields[] = {FN, LSOF, LCK, RXDM, RXDP};
  static constexpr Register reg{"USB_FS_device", "FNR", kBase, 0x48, fields};
};

struct Daddr {  // facts §5.2 DADDR (0x4C)
  static constexpr Field ADD{"ADD", 0, 7};
  static constexpr Field EF{"EF", 7, 1};  // enable function: the device answers only with EF
  static constexpr Field fields[] = {ADD, EF};
  static constexpr Register reg{"USB_FS_device", "DADDR", kBase, 0x4C, fields};
};

struct Btable {  // facts §5.2 BTABLE (0x50): PMA offset of the buffer table, 8-byte aligned
  static constexpr Field BTABLE{"BTABLE", 3, 13};
  static constexpr Field fields[] = {BTABLE};
  static constexpr Register reg{"USB_FS_device", "BTABLE", kBase, 0x50, fields};
};

/// BCDR (0x58): facts §5.1/§5.2 (CMSIS USB_BCDR_DPPU). ST's SVD has no BCDR (nor LPMCSR) in
/// USB_FS_device, so it is not in all.hpp's list; tests/stm32 asserts the SVD still lacks it.
struct Bcdr {
  static constexpr Field DPPU{"DPPU", 15, 1};  // the internal 1.5 kΩ pull-up on D+
  static constexpr Field fields[] = {DPPU};
  static constexpr Register reg{"USB_FS_device", "BCDR", kBase, 0x58, fields};
};

}  // namespace palp::stm32::usb
