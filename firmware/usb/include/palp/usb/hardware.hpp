// SPDX-License-Identifier: Apache-2.0
// Contract 1 (/work/team19.md): the USB device hardware interface. The device core
// (device.hpp, Device<H>) drives any H satisfying UsbHardware; the STM32G474's FSDEV driver
// (firmware/board/stm32g474/usb_fsdev.hpp) implements it, and the host tests implement it with a
// model of the peripheral. Names are fixed by the contract.
//
// Endpoints are named by NUMBER (0..7), not by address: number n stands for both directions
// (OUT n and IN n = 0x80|n), as on the FSDEV peripheral where one endpoint register carries both.
//
// Every member is non-blocking and may be called from the USB interrupt or from the main loop
// (never from both at once: the caller serialises).
//
// After a `reset` event the hardware has endpoint 0 open (control, max packet 64, ready to take a
// SETUP) and address 0; every other endpoint is closed. The core re-opens the others on
// SET_CONFIGURATION.
//
// Endpoint 0 always takes a SETUP (facts §1.11), whatever its state, and the SETUP cancels what
// ep0 had pending: an IN packet written but not taken, an armed OUT, a STALL. The core answers
// from the setup event on (write_in, arm_out or stall on ep0). The status stage the host sends
// after an IN data stage arrives as an `out` event on ep0 with 0 bytes (the core arms ep0 OUT
// for it). poll() reports events in the order they happened.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>

namespace palp::usb {

enum class EndpointType : std::uint8_t { control, bulk, interrupt };

/// What poll() reports:
///   none         nothing pending
///   reset        bus reset: address 0, ep0 open, every other endpoint closed
///   setup        a SETUP packet arrived on `endpoint` (read it with read_out: 8 bytes)
///   out          an OUT data packet arrived on `endpoint` (read_out; then arm_out for the next)
///   in_complete  the IN packet written with write_in on `endpoint` was taken by the host
///   suspend      the bus went idle for 3 ms
///   resume       bus activity after a suspend
enum class EventKind : std::uint8_t { none, reset, setup, out, in_complete, suspend, resume };

struct Event {
  EventKind kind = EventKind::none;
  std::uint8_t endpoint = 0;  ///< endpoint number 0..7
};

/// The 8 bytes of a SETUP packet (usb-dfu-facts.md §1), little-endian fields decoded.
struct SetupPacket {
  std::uint8_t bmRequestType, bRequest;
  std::uint16_t wValue, wIndex, wLength;
};

/// A UsbHardware H has:
///   Event poll();                  the next pending event (kind none: nothing pending)
///   void open_endpoint(std::uint8_t number, EndpointType type, std::uint16_t max_packet);
///                                  both directions of `number`: DATA0 toggles, no STALL, no IN
///                                  packet pending, OUT not armed (NAK) until arm_out; opening an
///                                  open endpoint again does the same (CLEAR_FEATURE(HALT))
///   std::size_t read_out(std::uint8_t number, std::uint8_t* bytes, std::size_t capacity);
///                                  the last SETUP/OUT packet's bytes on that endpoint (at most
///                                  capacity copied; returns the count copied)
///   void arm_out(std::uint8_t number);
///                                  accept the next OUT packet (RX VALID); until then the
///                                  hardware NAKs it (flow control)
///   void write_in(std::uint8_t number, const std::uint8_t* bytes, std::size_t size);
///                                  one IN packet (size <= max_packet; 0 = a zero-length packet,
///                                  bytes may then be null), copied before the call returns;
///                                  in_complete follows when the host took it. The core writes
///                                  the next only after that in_complete (or a re-open / SETUP)
///   void stall(std::uint8_t number);
///                                  STALL both directions; on ep0 until the next SETUP, on the
///                                  others until the endpoint is opened again (which also resets
///                                  its data toggles to DATA0: CLEAR_FEATURE(ENDPOINT_HALT))
///   void set_address(std::uint8_t address);
///                                  the device address; the core calls it after the status stage
///                                  of SET_ADDRESS
///   void connect(bool on);         the D+ pull-up (on: the host sees the device)
template <class H>
concept UsbHardware = requires(H& hw, std::uint8_t number, EndpointType type,
                               std::uint16_t max_packet, std::uint8_t* out_bytes,
                               const std::uint8_t* in_bytes, std::size_t size, bool on) {
  { hw.poll() } -> std::same_as<Event>;
  { hw.open_endpoint(number, type, max_packet) } -> std::same_as<void>;
  { hw.read_out(number, out_bytes, size) } -> std::same_as<std::size_t>;
  { hw.arm_out(number) } -> std::same_as<void>;
  { hw.write_in(number, in_bytes, size) } -> std::same_as<void>;
  { hw.stall(number) } -> std::same_as<void>;
  { hw.set_address(number) } -> std::same_as<void>;
  { hw.connect(on) } -> std::same_as<void>;
};

}  // namespace palp::usb
