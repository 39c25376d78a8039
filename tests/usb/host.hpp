// SPDX-License-Identifier: Apache-2.0
// The host's side of the device core's tests: control transfers, bulk and interrupt packets
// played on a bus (packet_bus.hpp's stand-in, or fsdev_bus.hpp's FSDEV model) the way a host
// controller does, running the device's service() (its USB interrupt) after every bus event. A transfer records every data packet's
// size, so tests can see a zero-length packet where the rules ask for one and nowhere else.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "packet_bus.hpp"
#include "palp/usb/hardware.hpp"

namespace palp::usb::test {

enum class Outcome { ok, stall, timeout };

struct ControlResult {
  Outcome outcome = Outcome::timeout;
  std::vector<std::uint8_t> data;    ///< the data stage's bytes (IN)
  std::vector<std::size_t> packets;  ///< each data packet's size, in order (IN)
};

template <class Bus>
class Host {
 public:
  /// `service` runs the device's interrupt handler; `naks_allowed` is how many NAKs in a row a
  /// transaction takes before the host gives up (a timeout).
  Host(Bus& bus, std::function<void()> service, int naks_allowed = 8)
      : bus_(bus), service_(std::move(service)), naks_allowed_(naks_allowed) {}

  std::uint8_t address = 0;  ///< the address the host sends to

  void reset() {
    bus_.bus_reset();
    address = 0;
    service_();
  }

  /// A control read: SETUP, IN packets until a short one or wLength bytes, the status OUT.
  /// `stop_after_packets` > 0 ends the data stage early (the status stage after that many
  /// packets), as Windows does with its first GET_DESCRIPTOR(DEVICE, 64).
  ControlResult control_in(const SetupPacket& s, std::size_t stop_after_packets = 0) {
    ControlResult r;
    if (bus_.setup(address, s) != Handshake::ack) return r;
    service_();
    for (;;) {
      InAnswer a = in_with_retries(0);
      if (a.handshake == Handshake::stall) return stalled(r);
      if (a.handshake != Handshake::ack) return r;
      r.packets.push_back(a.data.size());
      r.data.insert(r.data.end(), a.data.begin(), a.data.end());
      if (a.data.size() < 64 || r.data.size() >= s.wLength) break;
      if (stop_after_packets != 0 && r.packets.size() >= stop_after_packets) break;
    }
    const Handshake h = out_with_retries(0, nullptr, 0);
    if (h == Handshake::stall) return stalled(r);
    if (h != Handshake::ack) return r;
    r.outcome = Outcome::ok;
    return r;
  }

  /// A control write: SETUP, `data` in 64-byte OUT packets, the status IN (a zero-length packet).
  ControlResult control_out(const SetupPacket& s, const std::vector<std::uint8_t>& data = {}) {
    ControlResult r;
    if (bus_.setup(address, s) != Handshake::ack) return r;
    service_();
    for (std::size_t off = 0; off < data.size(); off += 64) {
      const std::size_t n = std::min<std::size_t>(64, data.size() - off);
      const Handshake h = out_with_retries(0, data.data() + off, n);
      if (h == Handshake::stall) return stalled(r);
      if (h != Handshake::ack) return r;
    }
    InAnswer a = in_with_retries(0);
    if (a.handshake == Handshake::stall) return stalled(r);
    if (a.handshake != Handshake::ack || !a.data.empty()) return r;
    r.outcome = Outcome::ok;
    return r;
  }

  /// One IN token, NAKs retried (with the device serviced between) up to the limit.
  InAnswer in_with_retries(std::uint8_t number) {
    for (int tries = 0;; ++tries) {
      InAnswer a = bus_.in(address, number);
      service_();
      if (a.handshake != Handshake::nak || tries >= naks_allowed_) return a;
    }
  }
  /// One OUT packet, NAKs retried likewise.
  Handshake out_with_retries(std::uint8_t number, const std::uint8_t* bytes, std::size_t n) {
    for (int tries = 0;; ++tries) {
      const Handshake h = bus_.out(address, number, bytes, n);
      service_();
      if (h != Handshake::nak || tries >= naks_allowed_) return h;
    }
  }

 private:
  static ControlResult& stalled(ControlResult& r) {
    r.outcome = Outcome::stall;
    return r;
  }

  Bus& bus_;
  std::function<void()> service_;
  int naks_allowed_;
};

/// SETUP packets of the requests the tests send (usb-dfu-facts.md §1.2, §2.2, §4.4).
inline SetupPacket get_descriptor(std::uint8_t type, std::uint8_t index, std::uint16_t length,
                                  std::uint16_t windex = 0, std::uint8_t request_type = 0x80) {
  return {request_type, 0x06, static_cast<std::uint16_t>(type << 8 | index), windex, length};
}
inline SetupPacket set_address(std::uint8_t address) { return {0x00, 0x05, address, 0, 0}; }
inline SetupPacket set_configuration(std::uint8_t value) { return {0x00, 0x09, value, 0, 0}; }

}  // namespace palp::usb::test
