// SPDX-License-Identifier: Apache-2.0
// A UsbHardware (contract 1, firmware/usb/include/palp/usb/hardware.hpp) for the device core's
// tests that plays the bus at the packet level, with the host's side as calls: a SETUP, an IN
// token, an OUT packet, a bus reset, suspend/resume. Each endpoint answers as the contract says
// the hardware does: an IN token gets the packet the device wrote (ACK), else NAK, or STALL; an
// OUT packet is taken (ACK) only when the device armed the endpoint, else NAK; a token to another
// address than the device's gets no answer. It also keeps each endpoint's data toggles, and
// records what the device did that contract 1 forbids (violations()), so a test can assert the
// device never did any.
//
// Written as the stand-in before the register-level FSDEV model existed; the typed
// tests now run on both (fsdev_bus.hpp), this one checking the contract itself.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "palp/usb/hardware.hpp"

namespace palp::usb::test {

enum class Handshake { ack, nak, stall, no_answer };

struct InAnswer {
  Handshake handshake = Handshake::no_answer;
  std::vector<std::uint8_t> data;  ///< the packet's bytes (ack only)
};

class PacketBus {
 public:
  static constexpr std::size_t kEndpoints = 8;
  /// What the device core drives: the bus itself.
  using Hardware = PacketBus;
  Hardware& hardware() { return *this; }

  // ---- contract 1: the device's side ---------------------------------------------------------
  Event poll() {
    if (events_.empty()) return {};
    const Event e = events_.front();
    events_.pop_front();
    return e;
  }
  void open_endpoint(std::uint8_t number, EndpointType type, std::uint16_t max_packet) {
    if (!check_number(number, "open_endpoint")) return;
    Endpoint& ep = ep_[number];
    const int opens = ep.opens;
    ep = Endpoint{};
    ep.opens = opens;
    ep.open = true;
    ep.type = type;
    ep.max_packet = max_packet;
    ++ep.opens;
  }
  std::size_t read_out(std::uint8_t number, std::uint8_t* bytes, std::size_t capacity) {
    if (!check_number(number, "read_out")) return 0;
    const auto& last = ep_[number].last_out;
    const std::size_t n = std::min(capacity, last.size());
    std::copy_n(last.begin(), n, bytes);
    return n;
  }
  void arm_out(std::uint8_t number) {
    if (!check_number(number, "arm_out")) return;
    if (!ep_[number].open) violation("arm_out on closed endpoint " + std::to_string(number));
    ep_[number].out_armed = true;
  }
  void write_in(std::uint8_t number, const std::uint8_t* bytes, std::size_t size) {
    if (!check_number(number, "write_in")) return;
    Endpoint& ep = ep_[number];
    if (!ep.open) violation("write_in on closed endpoint " + std::to_string(number));
    if (ep.in_pending) violation("write_in over a packet not yet taken on " + std::to_string(number));
    if (size > ep.max_packet) violation("write_in of " + std::to_string(size) + " bytes on " +
                                        std::to_string(number));
    ep.in_pending = true;
    ep.in_data.assign(bytes, bytes + size);
  }
  void stall(std::uint8_t number) {
    if (!check_number(number, "stall")) return;
    ep_[number].stalled = true;
    ep_[number].in_pending = false;
    ep_[number].out_armed = false;
    ++ep_[number].stalls;
  }
  void set_address(std::uint8_t address) {
    address_ = address;
    address_log_.push_back(address);
  }
  void connect(bool on) { connected_ = on; }

  // ---- the host's side -----------------------------------------------------------------------
  /// Bus reset: address 0, ep0 open (control, 64), the other endpoints closed; a reset event.
  void bus_reset() {
    for (Endpoint& ep : ep_) ep = Endpoint{};
    ep_[0].open = true;
    ep_[0].type = EndpointType::control;
    ep_[0].max_packet = 64;
    address_ = 0;
    events_.clear();
    events_.push_back({EventKind::reset, 0});
  }
  /// A SETUP to `address`: always taken by ep0 (it cancels what ep0 had pending and its STALL).
  Handshake setup(std::uint8_t address, const SetupPacket& s) {
    if (!connected_ || address != address_) return Handshake::no_answer;
    Endpoint& ep = ep_[0];
    ep.last_out = {s.bmRequestType, s.bRequest,
                   static_cast<std::uint8_t>(s.wValue), static_cast<std::uint8_t>(s.wValue >> 8),
                   static_cast<std::uint8_t>(s.wIndex), static_cast<std::uint8_t>(s.wIndex >> 8),
                   static_cast<std::uint8_t>(s.wLength), static_cast<std::uint8_t>(s.wLength >> 8)};
    ep.stalled = false;
    ep.in_pending = false;
    ep.out_armed = false;
    ep.toggle_in = 1;  // the data stage starts with DATA1 after a SETUP (DATA0)
    ep.toggle_out = 1;
    events_.push_back({EventKind::setup, 0});
    return Handshake::ack;
  }
  /// An IN token to endpoint `number` at `address`.
  InAnswer in(std::uint8_t address, std::uint8_t number) {
    if (!connected_ || address != address_ || number >= kEndpoints || !ep_[number].open)
      return {};
    Endpoint& ep = ep_[number];
    if (ep.stalled) return {Handshake::stall, {}};
    if (!ep.in_pending) return {Handshake::nak, {}};
    ep.in_pending = false;
    ep.toggle_in ^= 1;
    events_.push_back({EventKind::in_complete, number});
    return {Handshake::ack, ep.in_data};
  }
  /// An OUT packet to endpoint `number` at `address`.
  Handshake out(std::uint8_t address, std::uint8_t number, const std::uint8_t* bytes,
                std::size_t size) {
    if (!connected_ || address != address_ || number >= kEndpoints || !ep_[number].open)
      return Handshake::no_answer;
    Endpoint& ep = ep_[number];
    if (ep.stalled) return Handshake::stall;
    if (!ep.out_armed) return Handshake::nak;
    ep.out_armed = false;
    ep.toggle_out ^= 1;
    ep.last_out.assign(bytes, bytes + size);
    events_.push_back({EventKind::out, number});
    return Handshake::ack;
  }
  void suspend() { events_.push_back({EventKind::suspend, 0}); }
  void resume() { events_.push_back({EventKind::resume, 0}); }

  // ---- observations --------------------------------------------------------------------------
  std::uint8_t address() const { return address_; }
  const std::vector<std::uint8_t>& address_log() const { return address_log_; }
  bool connected() const { return connected_; }
  bool open(std::uint8_t number) const { return ep_[number].open; }
  EndpointType type(std::uint8_t number) const { return ep_[number].type; }
  std::uint16_t max_packet(std::uint8_t number) const { return ep_[number].max_packet; }
  bool stalled(std::uint8_t number) const { return ep_[number].stalled; }
  bool out_armed(std::uint8_t number) const { return ep_[number].out_armed; }
  bool in_pending(std::uint8_t number) const { return ep_[number].in_pending; }
  int toggle_in(std::uint8_t number) const { return ep_[number].toggle_in; }
  int toggle_out(std::uint8_t number) const { return ep_[number].toggle_out; }
  int opens(std::uint8_t number) const { return ep_[number].opens; }
  const std::vector<std::string>& violations() const { return violations_; }

 private:
  struct Endpoint {
    bool open = false;
    EndpointType type = EndpointType::control;
    std::uint16_t max_packet = 0;
    bool stalled = false, out_armed = false, in_pending = false;
    int toggle_in = 0, toggle_out = 0;  // DATA0 / DATA1 of the next packet
    int opens = 0, stalls = 0;
    std::vector<std::uint8_t> in_data, last_out;
  };

  bool check_number(std::uint8_t number, const char* what) {
    if (number < kEndpoints) return true;
    violation(std::string(what) + " on endpoint number " + std::to_string(number));
    return false;
  }
  void violation(std::string what) { violations_.push_back(std::move(what)); }

  std::array<Endpoint, kEndpoints> ep_{};
  std::deque<Event> events_;
  std::uint8_t address_ = 0;
  std::vector<std::uint8_t> address_log_;
  bool connected_ = false;
  std::vector<std::string> violations_;
};

static_assert(UsbHardware<PacketBus>);

}  // namespace palp::usb::test
