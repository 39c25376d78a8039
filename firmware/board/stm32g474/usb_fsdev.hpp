// SPDX-License-Identifier: Apache-2.0
// The STM32G474's USB full-speed device peripheral (FSDEV) as a palp::usb::UsbHardware
// (firmware/usb/include/palp/usb/hardware.hpp, contract 1 of the issue-20 team): endpoint
// registers, packet memory (PMA), bus events. Header-only over the register seam so the same code
// runs on the target (Mmio) and on the host against tests/stm32/fsdev_model.hpp. Facts:
// stm32g474-facts.md §5 (cited per step). Freestanding: no heap, no exceptions, never blocks.
//
// PMA layout (fixed; one 64-byte buffer per direction; facts §5.2 "PMA budget"):
//
//   PMA offset   bytes  what
//   0x000          64   buffer table (BTABLE = 0): 8 descriptors x 8 bytes, one per EPnR
//   0x040          64   EP0 RX  (SETUP and control OUT)
//   0x080          64   EP0 TX  (control IN)
//   0x0C0          64   EP1 RX  (bulk OUT)
//   0x100          64   EP1 TX  (bulk IN)
//   0x140          64   EP2 RX  (interrupt OUT)
//   0x180          64   EP2 TX  (interrupt IN)
//   0x1C0         576   free
//
// Endpoint number n uses EPnR n (EA = n), so numbers 0..2 can be opened, each with a max packet
// of 1..64 bytes. A call the layout or the state cannot honour (number > 2, closed endpoint, a
// packet over max_packet, an IN while the previous one is still pending, address > 127) does
// nothing and is counted: refusals() / last_refusal().
//
// Register writes follow facts §5.2/§5.3: EPnR only through write_epr() (toggle bits moved by
// writing current XOR wanted, both CTR bits written 1 except the one being cleared: never
// read-modify-write), ISTR flags cleared by writing their complement, CNTR/DADDR/BCDR/BTABLE
// written whole. The caller serialises calls (the USB interrupt or the main loop, not both).
#pragma once

#include <cstddef>
#include <cstdint>

#include "palp/usb/hardware.hpp"
#include "regs/rcc.hpp"
#include "regs/usb.hpp"

namespace palp::stm32::fsdev {

namespace dev = ::palp::usb;  // the contract (hardware.hpp); plain `usb::` is regs/usb.hpp

/// One endpoint's two PMA buffers (byte offsets in the PMA).
struct EndpointBuffers {
  std::uint16_t rx_offset;
  std::uint16_t tx_offset;
};

inline constexpr std::uint16_t kBtableOffset = 0x000;  // 8-byte aligned (facts §5.2 BTABLE)
inline constexpr std::uint16_t kDescriptorBytes = 8;   // ADDR_TX, COUNT_TX, ADDR_RX, COUNT_RX
inline constexpr std::uint16_t kBufferBytes = 64;      // FS bulk/interrupt/control max (§5.1)
inline constexpr std::uint8_t kEndpoints = 3;          // numbers 0, 1, 2
inline constexpr EndpointBuffers kLayout[kEndpoints] = {
    {0x040, 0x080}, {0x0C0, 0x100}, {0x140, 0x180}};

/// Offsets inside one buffer descriptor (facts §5.2 "BTABLE in PMA", 16-bit variant).
inline constexpr std::uint16_t kAddrTx = 0;
inline constexpr std::uint16_t kCountTx = 2;
inline constexpr std::uint16_t kAddrRx = 4;
inline constexpr std::uint16_t kCountRx = 6;
inline constexpr std::uint16_t kCountMask = 0x03FF;  // COUNTn_RX/TX COUNT[9:0]

/// The layout's rules: the table holds all 8 descriptors; every buffer is even, past the table,
/// inside the 1024-byte PMA and overlaps no other buffer.
constexpr bool layout_fits() {
  constexpr std::uint32_t table_end = kBtableOffset + kDescriptorBytes * usb::kEndpointRegisters;
  std::uint32_t starts[2 * kEndpoints] = {};
  for (std::uint8_t n = 0; n < kEndpoints; ++n) {
    starts[2 * n] = kLayout[n].rx_offset;
    starts[2 * n + 1] = kLayout[n].tx_offset;
  }
  for (std::uint32_t a : starts) {
    if (a % 2 != 0 || a < table_end || a + kBufferBytes > usb::kPmaSize) {
      return false;
    }
    for (std::uint32_t b : starts) {
      if (a != b && a < b + kBufferBytes && b < a + kBufferBytes) {
        return false;
      }
    }
  }
  return kBtableOffset % 8 == 0;
}
static_assert(layout_fits(), "the PMA layout must fit the 1024-byte PMA without overlaps");

/// COUNTn_RX's allocation bits for a buffer of `bytes` (1..1023; facts §5.2): BL_SIZE 0 with
/// NUM_BLOCK = bytes/2 rounded up up to 62 bytes, else BL_SIZE 1 with NUM_BLOCK = blocks of 32
/// minus one. The COUNT bits are 0.
constexpr std::uint16_t rx_allocation(std::uint16_t bytes) {
  if (bytes <= 62) {
    return static_cast<std::uint16_t>(((bytes + 1u) / 2u) << 10);
  }
  return static_cast<std::uint16_t>(0x8000u | ((((bytes + 31u) / 32u) - 1u) << 10));
}
static_assert(rx_allocation(64) == 0x8400 && rx_allocation(8) == 0x1000 &&
              rx_allocation(63) == 0x8400 && rx_allocation(62) == 0x7C00);

/// Why a call did nothing.
enum class Refusal : std::uint8_t {
  none,
  endpoint_out_of_range,    ///< number >= kEndpoints
  endpoint_closed,          ///< not opened since the last bus reset
  max_packet_out_of_range,  ///< open_endpoint with 0 or > 64
  packet_too_large,         ///< write_in over the endpoint's max_packet (or bytes null)
  in_pending,               ///< write_in while the previous IN is not yet taken
  address_out_of_range,     ///< set_address > 127
};

template <HalfwordAccess A>
class UsbFsdev {
 public:
  using Epr = usb::Epr;

  /// The interrupts the driver handles (CNTR while running): CTR, RESET, SUSP, WKUP.
  static constexpr std::uint32_t kCntrRun =
      usb::Cntr::CTRM.mask() | usb::Cntr::RESETM.mask() | usb::Cntr::SUSPM.mask() |
      usb::Cntr::WKUPM.mask();
  /// Reads of CNTR spent waiting t_STARTUP (≈ 1 µs, facts §5.3 item 1) after PDWN is cleared:
  /// each read takes at least one 170 MHz cycle, so 170 reads last at least 1 µs.
  static constexpr std::uint32_t kStartupReads = 170;

  explicit UsbFsdev(A& io) : io_(io) {}

  /// Clock enable, power-up, buffer table, endpoint 0 open (control, 64, ready for a SETUP),
  /// address 0 with EF, interrupts enabled. The D+ pull-up stays off: connect(true) attaches.
  /// The 48 MHz clock (HSI48 + CRS) is clock.hpp's.
  void init() {
    // RCC_APB1ENR1.USBEN (facts §2), read back once so the enable has reached the bus.
    write_field(io_, rcc::Apb1enr1::reg, rcc::Apb1enr1::USBEN, 1);
    (void)read(io_, rcc::Apb1enr1::reg);
    // Facts §5.3 item 1: FRES | PDWN, clear PDWN, wait t_STARTUP, clear FRES, clear ISTR.
    io_.write(usb::Cntr::reg.address(), usb::Cntr::FRES.mask() | usb::Cntr::PDWN.mask());
    io_.write(usb::Cntr::reg.address(), usb::Cntr::FRES.mask());
    for (std::uint32_t i = 0; i < kStartupReads; ++i) {
      (void)io_.read(usb::Cntr::reg.address());
    }
    io_.write(usb::Cntr::reg.address(), 0);
    io_.write(usb::Istr::reg.address(), 0);
    io_.write(usb::Btable::reg.address(), kBtableOffset);
    for (std::uint8_t n = 0; n < kEndpoints; ++n) {
      write_descriptor(n, kAddrTx, kLayout[n].tx_offset);
      write_descriptor(n, kCountTx, 0);
      write_descriptor(n, kAddrRx, kLayout[n].rx_offset);
      write_descriptor(n, kCountRx, rx_allocation(kBufferBytes));
    }
    bus_reset();
    io_.write(usb::Cntr::reg.address(), kCntrRun);
  }

  /// The next pending event, in the order reset, endpoint transfers (IN before OUT/SETUP on the
  /// same endpoint: on ep0 an IN that completed is older than the SETUP after it), suspend,
  /// wake-up. Each call handles and acknowledges one event.
  dev::Event poll() {
    // A SETUP with a count other than 8 is dropped (facts §5.3 item 6); bounded retries.
    for (int attempt = 0; attempt < 4 * usb::kEndpointRegisters; ++attempt) {
      const std::uint32_t istr = io_.read(usb::Istr::reg.address());
      if ((istr & usb::Istr::RESET.mask()) != 0) {
        clear_istr(usb::Istr::RESET);
        io_.write(usb::Cntr::reg.address(), kCntrRun);  // leaves suspend if it was in it
        bus_reset();
        return {dev::EventKind::reset, 0};
      }
      if ((istr & usb::Istr::CTR.mask()) != 0) {
        const auto n = static_cast<std::uint8_t>(usb::Istr::EP_ID.decode(istr));
        const dev::Event event = transfer_event(n);
        if (event.kind != dev::EventKind::none) {
          return event;
        }
        continue;
      }
      if ((istr & usb::Istr::SUSP.mask()) != 0) {
        // Facts §5.3 item 9: FSUSP, then LP_MODE, and only then clear SUSP.
        io_.write(usb::Cntr::reg.address(), kCntrRun | usb::Cntr::FSUSP.mask());
        io_.write(usb::Cntr::reg.address(),
                  kCntrRun | usb::Cntr::FSUSP.mask() | usb::Cntr::LP_MODE.mask());
        clear_istr(usb::Istr::SUSP);
        return {dev::EventKind::suspend, 0};
      }
      if ((istr & usb::Istr::WKUP.mask()) != 0) {
        io_.write(usb::Cntr::reg.address(), kCntrRun);  // LP_MODE and FSUSP off
        clear_istr(usb::Istr::WKUP);
        return {dev::EventKind::resume, 0};
      }
      return {};
    }
    return {};
  }

  /// Both directions of `number`: type, DATA0 toggles, RX and TX NAK (OUT not armed), any
  /// pending transfer flag dropped.
  void open_endpoint(std::uint8_t number, dev::EndpointType type, std::uint16_t max_packet) {
    if (number >= kEndpoints) {
      refuse(Refusal::endpoint_out_of_range);
      return;
    }
    if (max_packet == 0 || max_packet > kBufferBytes) {
      refuse(Refusal::max_packet_out_of_range);
      return;
    }
    max_packet_[number] = max_packet;
    write_descriptor(number, kCountTx, 0);
    write_descriptor(number, kCountRx, rx_allocation(max_packet));
    const std::uint32_t config = Epr::EP_TYPE.encode(type_code(type)) | Epr::EA.encode(number);
    write_epr(number, config, 0,
              Epr::STAT_RX.encode(Epr::kStatNak) | Epr::STAT_TX.encode(Epr::kStatNak) |
                  Epr::DTOG_RX.encode(0) | Epr::DTOG_TX.encode(0),
              kAllToggles);
  }

  /// The last SETUP/OUT packet on `number`: at most `capacity` bytes copied; the count copied.
  std::size_t read_out(std::uint8_t number, std::uint8_t* bytes, std::size_t capacity) {
    if (!usable(number)) {
      return 0;
    }
    std::size_t count = read_descriptor(number, kCountRx) & kCountMask;
    if (count > kBufferBytes) {
      count = kBufferBytes;
    }
    if (count > capacity) {
      count = capacity;
    }
    const std::uint32_t base = usb::kPmaBase + kLayout[number].rx_offset;
    for (std::size_t i = 0; i < count; i += 2) {
      const std::uint16_t half = io_.read16(static_cast<std::uint32_t>(base + i));
      bytes[i] = static_cast<std::uint8_t>(half & 0xFF);
      if (i + 1 < count) {
        bytes[i + 1] = static_cast<std::uint8_t>(half >> 8);
      }
    }
    return count;
  }

  /// Accept the next OUT packet: COUNTn_RX rewritten, then STAT_RX VALID (facts §5.3 item 7).
  void arm_out(std::uint8_t number) {
    if (!usable(number)) {
      return;
    }
    write_descriptor(number, kCountRx, rx_allocation(max_packet_[number]));
    write_epr(number, kKeepConfig, kCtrBits, Epr::STAT_RX.encode(Epr::kStatValid),
              Epr::STAT_RX.mask());
  }

  /// One IN packet of `size` bytes (0 = a zero-length packet): PMA, COUNTn_TX, STAT_TX VALID.
  void write_in(std::uint8_t number, const std::uint8_t* bytes, std::size_t size) {
    if (!usable(number)) {
      return;
    }
    if (size > max_packet_[number] || (bytes == nullptr && size != 0)) {
      refuse(Refusal::packet_too_large);
      return;
    }
    const std::uint32_t epr = io_.read(Epr::address(number));
    if (Epr::STAT_TX.decode(epr) == Epr::kStatValid) {
      refuse(Refusal::in_pending);
      return;
    }
    const std::uint32_t base = usb::kPmaBase + kLayout[number].tx_offset;
    for (std::size_t i = 0; i < size; i += 2) {
      const std::uint16_t high = i + 1 < size ? bytes[i + 1] : 0;
      io_.write16(static_cast<std::uint32_t>(base + i),
                  static_cast<std::uint16_t>(bytes[i] | (high << 8)));
    }
    write_descriptor(number, kCountTx, static_cast<std::uint16_t>(size));
    write_epr(number, kKeepConfig, kCtrBits, Epr::STAT_TX.encode(Epr::kStatValid),
              Epr::STAT_TX.mask());
  }

  /// STALL both directions; ep0's ends at the next SETUP (poll() sets both to NAK then), the
  /// others' when the endpoint is opened again.
  void stall(std::uint8_t number) {
    if (!usable(number)) {
      return;
    }
    write_epr(number, kKeepConfig, kCtrBits,
              Epr::STAT_RX.encode(Epr::kStatStall) | Epr::STAT_TX.encode(Epr::kStatStall),
              Epr::STAT_RX.mask() | Epr::STAT_TX.mask());
  }

  /// DADDR = EF | address (facts §5.2; called after the SET_ADDRESS status stage, §5.3 item 3).
  void set_address(std::uint8_t address) {
    if (address > 127) {
      refuse(Refusal::address_out_of_range);
      return;
    }
    io_.write(usb::Daddr::reg.address(), usb::Daddr::EF.mask() | usb::Daddr::ADD.encode(address));
  }

  /// BCDR.DPPU: the internal D+ pull-up (facts §5.1); off detaches (facts §5.3 item 12).
  void connect(bool on) {
    io_.write(usb::Bcdr::reg.address(), on ? usb::Bcdr::DPPU.mask() : 0u);
  }

  std::uint32_t refusals() const { return refusals_; }
  Refusal last_refusal() const { return last_refusal_; }

 private:
  static constexpr std::uint32_t kCtrBits = Epr::CTR_RX.mask() | Epr::CTR_TX.mask();
  static constexpr std::uint32_t kConfigBits =
      Epr::EP_TYPE.mask() | Epr::EP_KIND.mask() | Epr::EA.mask();
  static constexpr std::uint32_t kAllToggles =
      Epr::STAT_RX.mask() | Epr::STAT_TX.mask() | Epr::DTOG_RX.mask() | Epr::DTOG_TX.mask();
  static constexpr std::uint32_t kKeepConfig = 0xFFFF'FFFF;  // write_epr: keep EP_TYPE/KIND/EA
  // The facts sheet's recipe keeps exactly these bits (0x8F8F); none is a toggle bit.
  static_assert((kConfigBits | kCtrBits | Epr::SETUP.mask()) == Epr::kKeepMask);
  static_assert((kAllToggles & Epr::kKeepMask) == 0);

  static constexpr std::uint32_t type_code(dev::EndpointType type) {
    switch (type) {
      case dev::EndpointType::control:
        return Epr::kTypeControl;
      case dev::EndpointType::bulk:
        return Epr::kTypeBulk;
      case dev::EndpointType::interrupt:
        return Epr::kTypeInterrupt;
    }
    return Epr::kTypeBulk;
  }

  /// One write of EPnR by the safe recipe (facts §5.2): EP_TYPE/EP_KIND/EA = `config` (or the
  /// current ones for kKeepConfig); CTR_RX/CTR_TX written 1 (unchanged) except those in
  /// `clear_ctr`, written 0; each toggle bit in `toggle_mask` moved to its value in `wanted` by
  /// writing current XOR wanted, the other toggle bits written 0 (unchanged).
  void write_epr(std::uint8_t n, std::uint32_t config, std::uint32_t keep_ctr,
                 std::uint32_t wanted, std::uint32_t toggle_mask) {
    const std::uint32_t address = Epr::address(n);
    const std::uint32_t current = io_.read(address);
    const std::uint32_t rw = config == kKeepConfig ? (current & kConfigBits) : config;
    io_.write(address, rw | (keep_ctr & kCtrBits) | ((current ^ wanted) & toggle_mask));
  }

  void clear_istr(const Field& flag) { io_.write(usb::Istr::reg.address(), ~flag.mask() & 0xFFFF); }

  /// The event of EPnR n's pending CTR bit (CTR_TX first), acknowledged; none if neither is set.
  dev::Event transfer_event(std::uint8_t n) {
    const std::uint32_t epr = io_.read(Epr::address(n));
    const auto number = static_cast<std::uint8_t>(Epr::EA.decode(epr));
    if ((epr & Epr::CTR_TX.mask()) != 0) {
      write_epr(n, kKeepConfig, Epr::CTR_RX.mask(), 0, 0);
      return {dev::EventKind::in_complete, number};
    }
    if ((epr & Epr::CTR_RX.mask()) == 0) {
      return {};
    }
    if ((epr & Epr::SETUP.mask()) == 0) {
      write_epr(n, kKeepConfig, Epr::CTR_TX.mask(), 0, 0);
      return {dev::EventKind::out, number};
    }
    if ((read_descriptor(n, kCountRx) & kCountMask) != 8) {
      // A SETUP that is not 8 bytes was a damaged or missed packet: drop it, take the next.
      write_epr(n, kKeepConfig, Epr::CTR_TX.mask(), Epr::STAT_RX.encode(Epr::kStatValid),
                Epr::STAT_RX.mask());
      return {};
    }
    // A SETUP ends any STALL and any IN still queued: both NAK, both toggles DATA1 for the
    // data and status stages (the data stage starts with DATA1 whatever came before).
    write_epr(n, kKeepConfig, Epr::CTR_TX.mask(),
              Epr::STAT_RX.encode(Epr::kStatNak) | Epr::STAT_TX.encode(Epr::kStatNak) |
                  Epr::DTOG_RX.mask() | Epr::DTOG_TX.mask(),
              kAllToggles);
    return {dev::EventKind::setup, number};
  }

  /// After a bus reset (facts §5.3 item 2): every endpoint closed and disabled, ep0 open
  /// (control, 64) with RX VALID, DADDR = EF | 0.
  void bus_reset() {
    for (std::uint8_t n = 0; n < usb::kEndpointRegisters; ++n) {
      write_epr(n, 0, 0,
                Epr::STAT_RX.encode(Epr::kStatDisabled) | Epr::STAT_TX.encode(Epr::kStatDisabled),
                Epr::STAT_RX.mask() | Epr::STAT_TX.mask());
    }
    for (std::uint16_t& mp : max_packet_) {
      mp = 0;
    }
    open_endpoint(0, dev::EndpointType::control, kBufferBytes);
    arm_out(0);
    io_.write(usb::Daddr::reg.address(), usb::Daddr::EF.mask());
  }

  bool usable(std::uint8_t number) {
    if (number >= kEndpoints) {
      refuse(Refusal::endpoint_out_of_range);
      return false;
    }
    if (max_packet_[number] == 0) {
      refuse(Refusal::endpoint_closed);
      return false;
    }
    return true;
  }

  void refuse(Refusal why) {
    ++refusals_;
    last_refusal_ = why;
  }

  std::uint32_t descriptor_address(std::uint8_t n, std::uint16_t field) const {
    return usb::kPmaBase + kBtableOffset + kDescriptorBytes * n + field;
  }
  void write_descriptor(std::uint8_t n, std::uint16_t field, std::uint16_t value) {
    io_.write16(descriptor_address(n, field), value);
  }
  std::uint16_t read_descriptor(std::uint8_t n, std::uint16_t field) {
    return io_.read16(descriptor_address(n, field));
  }

  A& io_;
  std::uint16_t max_packet_[kEndpoints] = {};  // 0 = closed
  std::uint32_t refusals_ = 0;
  Refusal last_refusal_ = Refusal::none;
};

static_assert(dev::UsbHardware<UsbFsdev<Mmio>>);

}  // namespace palp::stm32::fsdev
