// SPDX-License-Identifier: Apache-2.0
// A register-level model of the STM32G474 USB device peripheral (FSDEV), written from
// stm32g474-facts.md §5 — not from the driver (usb_fsdev.hpp) — for host tests. It has two
// sides:
//
// * The device side is an Access for the register seam (regs/register.hpp, HalfwordAccess):
//   32-bit read/write of the USB registers with their write semantics (§5.2: CTR_RX/CTR_TX and
//   the ISTR flags rc_w0, STAT_RX/STAT_TX/DTOG_RX/DTOG_TX toggle on a written 1, SETUP, ISTR
//   CTR/DIR/EP_ID and FNR read-only), 16-bit read16/write16 of the 1024-byte PMA (§5.1: 16-bit
//   accesses only, byte offset N at 0x4000_6000 + N), and a plain word store for any other
//   address (the RCC enable the driver writes). USB accesses while RCC_APB1ENR1.USBEN is 0, a
//   32-bit access to the PMA, an odd or out-of-range PMA address and a write to a read-only
//   register are counted as faults() and otherwise ignored.
// * The host side plays the bus: bus_reset(), setup(), out(), in(), suspend(), resume(). Packets
//   go through the buffer table in the PMA (§5.2 "BTABLE in PMA": ADDR_TX +0, COUNT_TX +2,
//   ADDR_RX +4, COUNT_RX +6 at BTABLE + 8n; decoded here independently of the driver) and the
//   EPnR whose EA is the token's endpoint number. The host keeps its own DATA0/DATA1 toggle per
//   endpoint and direction and counts every packet whose toggle disagrees with the device's.
//
// What the facts sheet does not say, and the model assumes (RM0440 to confirm):
// * The device answers only when USBEN, CNTR.PDWN = 0, CNTR.FRES = 0, BCDR.DPPU = 1 (attached),
//   DADDR.EF = 1 and the token's address equals DADDR.ADD.
// * A bus reset sets ISTR.RESET and clears every EPnR and DADDR (communication disabled until
//   the firmware re-programs endpoint 0 and sets EF, facts §5.3 item 2).
// * A SETUP to a control endpoint is taken whatever its STAT_RX but DISABLED (USB requires a
//   device to accept every SETUP, usb-dfu-facts.md §1.11; this is what lets an ep0 STALL end at
//   the next SETUP). It needs room for 8 bytes, sets CTR_RX and SETUP, STAT_RX NAK, and leaves
//   STAT_TX and both DTOG bits alone (the driver sets what the data stage needs).
// * A successful OUT/SETUP sets STAT_RX to NAK and an IN taken sets STAT_TX to NAK (the firmware
//   re-arms each packet, facts §5.3 item 7); an OUT with the wrong toggle is ACKed and dropped.
// * An OUT larger than the COUNT_RX allocation gets no handshake (rx_overflows()).
// * ISTR.CTR is set while any EPnR has CTR_RX or CTR_TX; EP_ID is the lowest such EPnR; DIR is 1
//   when that EPnR has CTR_RX.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <vector>

#include "regs/rcc.hpp"
#include "regs/usb.hpp"

namespace palp::stm32::test {

/// The device's answer to a token (none: no answer at all, the host times out).
enum class Handshake : std::uint8_t { ack, nak, stall, none };

struct InPacket {
  Handshake handshake = Handshake::none;
  std::uint8_t pid_data = 0;  ///< 0 = DATA0, 1 = DATA1 (meaningful with ack)
  std::vector<std::uint8_t> bytes;
};

/// Accesses the real peripheral would not take or would ignore (each counted once per access).
struct FsdevFaults {
  std::uint32_t without_clock = 0;     ///< a USB register or PMA access with USBEN = 0
  std::uint32_t pma_wide = 0;          ///< a 32-bit access to the PMA
  std::uint32_t pma_misaligned = 0;    ///< read16/write16 at an odd address or outside the PMA
  std::uint32_t read_only_write = 0;   ///< a write to FNR
  std::uint32_t buffer_outside = 0;    ///< a packet whose PMA buffer lies outside the PMA or odd
  std::uint32_t tx_count_invalid = 0;  ///< an IN taken with COUNT_TX over 64 (FS max packet)

  std::uint32_t total() const {
    return without_clock + pma_wide + pma_misaligned + read_only_write + buffer_outside +
           tx_count_invalid;
  }
};

class FsdevModel {
 public:
  struct Write {
    std::uint32_t address;
    std::uint32_t value;
    std::uint64_t reads_before;  ///< reads (of anything) done before this write
  };

  FsdevModel() { cntr_ = usb::Cntr::FRES.mask() | usb::Cntr::PDWN.mask(); }  // §5.3 item 1

  // ---- Device side: the Access the driver runs on ----

  std::uint32_t read(std::uint32_t address) {
    ++reads_;
    std::uint32_t value = 0;
    if (in_pma(address)) {
      ++faults_.pma_wide;
    } else if (!is_usb_register(address)) {
      const auto it = words_.find(address);
      value = it == words_.end() ? 0 : it->second;
    } else if (!clocked()) {
      ++faults_.without_clock;
    } else {
      value = read_usb(address - usb::kBase);
    }
    return value;
  }

  void write(std::uint32_t address, std::uint32_t value) {
    if (logging_) {
      log_.push_back({address, value, reads_});
    }
    run_hook(address);
    if (in_pma(address)) {
      ++faults_.pma_wide;
    } else if (!is_usb_register(address)) {
      words_[address] = value;
    } else if (!clocked()) {
      ++faults_.without_clock;
    } else {
      write_usb(address - usb::kBase, value & 0xFFFF);
    }
  }

  std::uint16_t read16(std::uint32_t address) {
    ++reads_;
    std::uint16_t value = 0;
    if (pma_ok(address)) {
      const std::uint32_t at = address - usb::kPmaBase;
      value = static_cast<std::uint16_t>(pma_[at] | (pma_[at + 1] << 8));
    }
    return value;
  }

  void write16(std::uint32_t address, std::uint16_t value) {
    if (pma_ok(address)) {
      const std::uint32_t at = address - usb::kPmaBase;
      pma_[at] = static_cast<std::uint8_t>(value & 0xFF);
      pma_[at + 1] = static_cast<std::uint8_t>(value >> 8);
    }
  }

  // ---- Host side: the bus ----

  /// SE0 for 10 ms: ISTR.RESET; EPnR and DADDR cleared; the host talks to address 0, DATA0.
  void bus_reset() {
    if (!clocked() || !attached()) {
      return;
    }
    flags_ |= usb::Istr::RESET.mask();
    epr_.fill(0);
    daddr_ = 0;
    host_address_ = 0;
    host_out_toggle_.fill(0);
    host_in_toggle_.fill(0);
  }

  /// A SETUP (DATA0, 8 bytes) to endpoint `ep`; the host's toggles of `ep` become DATA1 on ACK.
  /// Any other size plays the damaged SETUP of facts §5.3 item 6 (a COUNT other than 8).
  Handshake setup(std::uint8_t ep, std::span<const std::uint8_t> bytes) {
    const int n = answering_epr(ep, usb::Epr::STAT_RX);
    if (n < 0 || usb::Epr::EP_TYPE.decode(epr_[n]) != usb::Epr::kTypeControl) {
      return Handshake::none;
    }
    if (!receive(static_cast<std::uint8_t>(n), bytes, true)) {
      return Handshake::none;
    }
    epr_[n] |= usb::Epr::SETUP.mask();
    host_out_toggle_[ep] = 1;
    host_in_toggle_[ep] = 1;
    return Handshake::ack;
  }

  /// An OUT data packet (the host's current toggle for `ep`) of 0..64 bytes.
  Handshake out(std::uint8_t ep, std::span<const std::uint8_t> bytes) {
    const int n = answering_epr(ep, usb::Epr::STAT_RX);
    if (n < 0 || bytes.size() > 64) {
      return Handshake::none;
    }
    const std::uint32_t stat = usb::Epr::STAT_RX.decode(epr_[n]);
    if (stat == usb::Epr::kStatStall) {
      return Handshake::stall;
    }
    if (stat == usb::Epr::kStatNak) {
      return Handshake::nak;
    }
    if (host_out_toggle_[ep] != usb::Epr::DTOG_RX.decode(epr_[n])) {
      ++toggle_mismatches_;  // the device ACKs and drops a packet it takes for a repeat
      return Handshake::ack;
    }
    if (!receive(static_cast<std::uint8_t>(n), bytes, false)) {
      return Handshake::none;
    }
    host_out_toggle_[ep] ^= 1;
    return Handshake::ack;
  }

  /// An IN token to `ep`: the TX buffer's COUNT_TX bytes with DTOG_TX as the PID when VALID.
  InPacket in(std::uint8_t ep) {
    InPacket packet;
    const int n = answering_epr(ep, usb::Epr::STAT_TX);
    if (n < 0) {
      return packet;
    }
    std::uint32_t& reg = epr_[n];
    const std::uint32_t stat = usb::Epr::STAT_TX.decode(reg);
    if (stat != usb::Epr::kStatValid) {
      packet.handshake = stat == usb::Epr::kStatStall ? Handshake::stall : Handshake::nak;
      return packet;
    }
    const std::uint16_t address = descriptor(static_cast<std::uint8_t>(n), kAddrTx);
    const std::uint16_t count = descriptor(static_cast<std::uint8_t>(n), kCountTx) & 0x03FF;
    if (count > 64) {
      ++faults_.tx_count_invalid;
      return packet;
    }
    if (!buffer_inside(address, count)) {
      return packet;
    }
    packet.bytes.assign(pma_.begin() + address, pma_.begin() + address + count);
    packet.pid_data = static_cast<std::uint8_t>(usb::Epr::DTOG_TX.decode(reg));
    packet.handshake = Handshake::ack;
    reg ^= usb::Epr::DTOG_TX.mask();
    set_stat(reg, usb::Epr::STAT_TX, usb::Epr::kStatNak);
    reg |= usb::Epr::CTR_TX.mask();
    if (packet.pid_data != host_in_toggle_[ep]) {
      ++toggle_mismatches_;  // the host ACKs and drops what it takes for a repeat
    } else {
      host_in_toggle_[ep] ^= 1;
    }
    return packet;
  }

  /// 3 ms of idle bus: ISTR.SUSP. Bus activity again: ISTR.WKUP.
  void suspend() { flags_ |= usb::Istr::SUSP.mask(); }
  void resume() { flags_ |= usb::Istr::WKUP.mask(); }

  /// The address the host's tokens carry (after its SET_ADDRESS's status stage).
  void set_host_address(std::uint8_t address) { host_address_ = address; }
  /// The host's toggles of `ep` back to DATA0 (SET_CONFIGURATION, CLEAR_FEATURE(ENDPOINT_HALT)).
  void reset_host_toggles(std::uint8_t ep) {
    host_out_toggle_[ep] = 0;
    host_in_toggle_[ep] = 0;
  }

  /// IN tokens until the answer is not NAK, running `device` (e.g. the driver's poll loop)
  /// before each retry; at most `tries` tokens.
  InPacket in_retrying(std::uint8_t ep, const std::function<void()>& device, int tries = 8) {
    InPacket packet = in(ep);
    for (int i = 1; i < tries && packet.handshake == Handshake::nak; ++i) {
      device();
      packet = in(ep);
    }
    return packet;
  }
  Handshake out_retrying(std::uint8_t ep, std::span<const std::uint8_t> bytes,
                         const std::function<void()>& device, int tries = 8) {
    Handshake answer = out(ep, bytes);
    for (int i = 1; i < tries && answer == Handshake::nak; ++i) {
      device();
      answer = out(ep, bytes);
    }
    return answer;
  }

  // ---- Inspection ----

  /// Runs `action` once, right before the next write to `address` takes effect: a bus event
  /// between the driver's last read of a register and its write, what breaks read-modify-write.
  void before_next_write(std::uint32_t address, std::function<void()> action) {
    hook_address_ = address;
    hook_ = std::move(action);
  }

  std::uint32_t epr(std::uint8_t n) const { return epr_[n]; }
  std::uint32_t cntr() const { return cntr_; }
  std::uint32_t istr() const { return istr_value(); }
  std::uint32_t daddr() const { return daddr_; }
  std::uint32_t btable() const { return btable_; }
  bool attached() const { return (bcdr_ & usb::Bcdr::DPPU.mask()) != 0; }
  /// The buffer-table entry `field` (kAddrTx.. kCountRx) of EPnR n, as the peripheral reads it.
  std::uint16_t descriptor(std::uint8_t n, std::uint16_t field) const {
    return pma16(static_cast<std::uint16_t>(btable_ + 8 * n + field));
  }
  /// COUNT_RX's allocation in bytes (facts §5.2: BL_SIZE 0 → 2 × NUM_BLOCK, 1 → 32 × (NUM_BLOCK
  /// + 1)); 0 for the invalid all-zero encoding.
  std::uint16_t rx_allocation(std::uint8_t n) const {
    const std::uint16_t count_rx = descriptor(n, kCountRx);
    const std::uint16_t blocks = (count_rx >> 10) & 0x1F;
    if ((count_rx & 0x8000) != 0) {
      return static_cast<std::uint16_t>(32 * (blocks + 1));
    }
    return static_cast<std::uint16_t>(2 * blocks);
  }
  std::uint16_t pma16(std::uint16_t offset) const {
    return static_cast<std::uint16_t>(pma_[offset % kPma] | (pma_[(offset + 1) % kPma] << 8));
  }
  const FsdevFaults& faults() const { return faults_; }
  std::uint32_t toggle_mismatches() const { return toggle_mismatches_; }
  std::uint32_t rx_overflows() const { return rx_overflows_; }
  /// Times ISTR.SUSP was cleared while CNTR.FSUSP was 0 (facts §5.3 item 9 says FSUSP first).
  std::uint32_t suspend_cleared_early() const { return suspend_cleared_early_; }
  const std::vector<Write>& log() const { return log_; }
  /// Off: writes are no longer logged (long transfers).
  void set_logging(bool on) { logging_ = on; }
  std::uint64_t reads() const { return reads_; }

  static constexpr std::uint16_t kAddrTx = 0, kCountTx = 2, kAddrRx = 4, kCountRx = 6;

 private:
  static constexpr std::uint32_t kPma = usb::kPmaSize;
  static constexpr std::uint32_t kFlagBits =
      usb::Istr::PMAOVR.mask() | usb::Istr::ERR.mask() | usb::Istr::WKUP.mask() |
      usb::Istr::SUSP.mask() | usb::Istr::RESET.mask() | usb::Istr::SOF.mask() |
      usb::Istr::ESOF.mask() | (1u << 7);  // L1REQ
  static constexpr std::uint32_t kToggleBits = usb::Epr::STAT_RX.mask() |
                                               usb::Epr::DTOG_RX.mask() |
                                               usb::Epr::STAT_TX.mask() | usb::Epr::DTOG_TX.mask();
  static constexpr std::uint32_t kRwBits =
      usb::Epr::EP_TYPE.mask() | usb::Epr::EP_KIND.mask() | usb::Epr::EA.mask();

  static bool in_pma(std::uint32_t address) {
    return address >= usb::kPmaBase && address < usb::kPmaBase + kPma;
  }
  static bool is_usb_register(std::uint32_t address) {
    return address >= usb::kBase && address < usb::kBase + 0x5C;
  }
  bool clocked() const {
    const auto it = words_.find(rcc::Apb1enr1::reg.address());
    return it != words_.end() && rcc::Apb1enr1::USBEN.decode(it->second) != 0;
  }
  bool pma_ok(std::uint32_t address) {
    if (!in_pma(address) || address % 2 != 0) {
      ++faults_.pma_misaligned;
      return false;
    }
    if (!clocked()) {
      ++faults_.without_clock;
      return false;
    }
    return true;
  }

  std::uint32_t istr_value() const {
    std::uint32_t value = flags_;
    for (std::uint8_t n = 0; n < usb::kEndpointRegisters; ++n) {
      const bool rx = (epr_[n] & usb::Epr::CTR_RX.mask()) != 0;
      if (rx || (epr_[n] & usb::Epr::CTR_TX.mask()) != 0) {
        value |= usb::Istr::CTR.mask() | usb::Istr::EP_ID.encode(n) |
                 (rx ? usb::Istr::DIR.mask() : 0u);
        break;
      }
    }
    return value;
  }

  std::uint32_t read_usb(std::uint32_t offset) const {
    if (offset < 4u * usb::kEndpointRegisters) {
      return offset % 4 == 0 ? epr_[offset / 4] : 0;
    }
    switch (offset) {
      case 0x40: return cntr_;
      case 0x44: return istr_value();
      case 0x48: return 0;  // FNR: no SOFs are modelled
      case 0x4C: return daddr_;
      case 0x50: return btable_;
      case 0x58: return bcdr_;
      default: return 0;
    }
  }

  void write_usb(std::uint32_t offset, std::uint32_t value) {
    if (offset < 4u * usb::kEndpointRegisters) {
      if (offset % 4 == 0) {
        write_epr(epr_[offset / 4], value);
      }
      return;
    }
    switch (offset) {
      case 0x40: cntr_ = value; break;
      case 0x44:
        if ((flags_ & usb::Istr::SUSP.mask()) != 0 && (value & usb::Istr::SUSP.mask()) == 0 &&
            (cntr_ & usb::Cntr::FSUSP.mask()) == 0) {
          ++suspend_cleared_early_;
        }
        flags_ &= value | ~kFlagBits;  // rc_w0; CTR, DIR, EP_ID are read-only
        break;
      case 0x48: ++faults_.read_only_write; break;
      case 0x4C: daddr_ = value & 0xFF; break;
      case 0x50: btable_ = value & 0xFFF8; break;
      case 0x58: bcdr_ = value; break;
      default: break;
    }
  }

  /// EPnR write semantics (facts §5.2).
  static void write_epr(std::uint32_t& reg, std::uint32_t value) {
    std::uint32_t next = reg & usb::Epr::SETUP.mask();                    // read-only
    next |= value & kRwBits;                                              // rw
    next |= (reg ^ value) & kToggleBits;                                  // toggle on 1
    next |= reg & value & (usb::Epr::CTR_RX.mask() | usb::Epr::CTR_TX.mask());  // rc_w0
    reg = next;
  }

  static void set_stat(std::uint32_t& reg, const Field& stat, std::uint32_t code) {
    reg = (reg & ~stat.mask()) | stat.encode(code);
  }

  bool answering() const {
    return clocked() && (cntr_ & (usb::Cntr::PDWN.mask() | usb::Cntr::FRES.mask())) == 0 &&
           attached() && usb::Daddr::EF.decode(daddr_) != 0 &&
           usb::Daddr::ADD.decode(daddr_) == host_address_;
  }

  /// The EPnR that answers a token to endpoint `ep` in the direction of `stat`: the lowest n
  /// with EA = ep and that direction not DISABLED; -1 when none (or the device is not there).
  int answering_epr(std::uint8_t ep, const Field& stat) const {
    if (!answering() || ep >= 16) {
      return -1;
    }
    for (std::uint8_t n = 0; n < usb::kEndpointRegisters; ++n) {
      if (usb::Epr::EA.decode(epr_[n]) == ep && stat.decode(epr_[n]) != usb::Epr::kStatDisabled) {
        return n;
      }
    }
    return -1;
  }

  bool buffer_inside(std::uint32_t address, std::uint32_t size) {
    if (address % 2 != 0 || address + size > kPma) {
      ++faults_.buffer_outside;
      return false;
    }
    return true;
  }

  /// A packet into EPnR n's RX buffer: COUNT set, CTR_RX, DTOG_RX toggled (not for a SETUP),
  /// STAT_RX NAK, SETUP cleared. False (no handshake) when it does not fit.
  bool receive(std::uint8_t n, std::span<const std::uint8_t> bytes, bool is_setup) {
    const std::uint16_t address = descriptor(n, kAddrRx);
    const std::uint16_t allocation = rx_allocation(n);
    if (allocation == 0 || bytes.size() > allocation) {
      ++rx_overflows_;
      return false;
    }
    if (!buffer_inside(address, allocation)) {
      return false;
    }
    std::copy(bytes.begin(), bytes.end(), pma_.begin() + address);
    const std::uint16_t at = static_cast<std::uint16_t>(btable_ + 8 * n + kCountRx);
    const std::uint16_t count_rx =
        static_cast<std::uint16_t>((descriptor(n, kCountRx) & 0xFC00) | bytes.size());
    pma_[at % kPma] = static_cast<std::uint8_t>(count_rx & 0xFF);
    pma_[(at + 1) % kPma] = static_cast<std::uint8_t>(count_rx >> 8);
    std::uint32_t& reg = epr_[n];
    if (!is_setup) {
      reg ^= usb::Epr::DTOG_RX.mask();
    }
    reg &= ~usb::Epr::SETUP.mask();
    set_stat(reg, usb::Epr::STAT_RX, usb::Epr::kStatNak);
    reg |= usb::Epr::CTR_RX.mask();
    return true;
  }

  void run_hook(std::uint32_t address) {
    if (hook_ && address == hook_address_) {
      auto action = std::move(hook_);
      hook_ = nullptr;
      action();
    }
  }

  std::map<std::uint32_t, std::uint32_t> words_;  // non-USB registers (RCC)
  std::array<std::uint32_t, usb::kEndpointRegisters> epr_{};
  std::array<std::uint8_t, kPma> pma_{};
  std::uint32_t cntr_ = 0, flags_ = 0, daddr_ = 0, btable_ = 0, bcdr_ = 0;
  std::uint8_t host_address_ = 0;
  std::array<std::uint8_t, 16> host_out_toggle_{}, host_in_toggle_{};
  FsdevFaults faults_;
  std::uint32_t toggle_mismatches_ = 0, rx_overflows_ = 0, suspend_cleared_early_ = 0;
  std::vector<Write> log_;
  bool logging_ = true;
  std::uint64_t reads_ = 0;
  std::uint32_t hook_address_ = 0;
  std::function<void()> hook_;
};

static_assert(HalfwordAccess<FsdevModel>);

}  // namespace palp::stm32::test
