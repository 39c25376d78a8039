// SPDX-License-Identifier: Apache-2.0
// The device core on the STM32G474's FSDEV driver (firmware/board/stm32g474/usb_fsdev.hpp) over
// the register-level model of the peripheral (tests/stm32/fsdev_model.hpp): the
// same host calls and observations as PacketBus (packet_bus.hpp), answered by the model's
// registers and PMA. Built when the tree has the model (tests/usb/CMakeLists.txt: target
// palp_stm32_fsdev_model), so every typed test runs on both buses.
//
// As a host does, the bus resets its own data toggles of an endpoint once a request that resets
// the device's (SET_CONFIGURATION, SET_INTERFACE, CLEAR_FEATURE(ENDPOINT_HALT)) has completed;
// a toggle the device did not reset then shows as a toggle mismatch, one of the violations().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fsdev_model.hpp"
#include "packet_bus.hpp"
#include "palp/usb/hardware.hpp"
#include "usb_fsdev.hpp"

namespace palp::usb::test {

using FsdevModel = ::palp::stm32::test::FsdevModel;
using FsdevDriver = ::palp::stm32::fsdev::UsbFsdev<FsdevModel>;

/// Contract 1 forwarded to the FSDEV driver, noting the calls the tests observe.
class FsdevHardware {
 public:
  explicit FsdevHardware(FsdevDriver& driver) : driver_(driver) {}
  Event poll() { return driver_.poll(); }
  void open_endpoint(std::uint8_t number, EndpointType type, std::uint16_t max_packet) {
    if (number < opens.size()) ++opens[number];
    driver_.open_endpoint(number, type, max_packet);
  }
  std::size_t read_out(std::uint8_t number, std::uint8_t* bytes, std::size_t capacity) {
    return driver_.read_out(number, bytes, capacity);
  }
  void arm_out(std::uint8_t number) { driver_.arm_out(number); }
  void write_in(std::uint8_t number, const std::uint8_t* bytes, std::size_t size) {
    driver_.write_in(number, bytes, size);
  }
  void stall(std::uint8_t number) { driver_.stall(number); }
  void set_address(std::uint8_t address) {
    address_log.push_back(address);
    driver_.set_address(address);
  }
  void connect(bool on) { driver_.connect(on); }

  std::array<int, 8> opens{};
  std::vector<std::uint8_t> address_log;

 private:
  FsdevDriver& driver_;
};
static_assert(UsbHardware<FsdevHardware>);

class FsdevBus {
 public:
  using Hardware = FsdevHardware;
  using Epr = ::palp::stm32::usb::Epr;

  FsdevBus() {
    model_.set_logging(false);  // millions of writes in the bulk tests
    driver_.init();
  }
  Hardware& hardware() { return hw_; }

  // ---- the host's side (as PacketBus) ----------------------------------------------------------
  void bus_reset() {
    model_.bus_reset();
    toggle_resets_.clear();
  }
  Handshake setup(std::uint8_t address, const SetupPacket& s) {
    model_.set_host_address(address);
    const std::array<std::uint8_t, 8> bytes = {
        s.bmRequestType, s.bRequest,
        static_cast<std::uint8_t>(s.wValue), static_cast<std::uint8_t>(s.wValue >> 8),
        static_cast<std::uint8_t>(s.wIndex), static_cast<std::uint8_t>(s.wIndex >> 8),
        static_cast<std::uint8_t>(s.wLength), static_cast<std::uint8_t>(s.wLength >> 8)};
    note_toggle_resets(s);
    return handshake(model_.setup(0, bytes));
  }
  InAnswer in(std::uint8_t address, std::uint8_t number) {
    model_.set_host_address(address);
    auto packet = model_.in(number);
    InAnswer a{handshake(packet.handshake), std::move(packet.bytes)};
    if (number == 0 && a.handshake == Handshake::ack && a.data.empty()) {
      for (std::uint8_t ep : toggle_resets_) model_.reset_host_toggles(ep);  // request done
      toggle_resets_.clear();
    }
    return a;
  }
  Handshake out(std::uint8_t address, std::uint8_t number, const std::uint8_t* bytes,
                std::size_t size) {
    model_.set_host_address(address);
    return handshake(model_.out(number, std::span<const std::uint8_t>(bytes, size)));
  }
  void suspend() { model_.suspend(); }
  void resume() { model_.resume(); }

  // ---- observations, from the registers ----------------------------------------------------
  std::uint8_t address() const { return static_cast<std::uint8_t>(model_.daddr() & 0x7F); }
  const std::vector<std::uint8_t>& address_log() const { return hw_.address_log; }
  bool connected() const { return model_.attached(); }
  bool open(std::uint8_t number) const {
    return Epr::EA.decode(model_.epr(number)) == number && model_.rx_allocation(number) > 0;
  }
  EndpointType type(std::uint8_t number) const {
    switch (Epr::EP_TYPE.decode(model_.epr(number))) {
      case Epr::kTypeBulk: return EndpointType::bulk;
      case Epr::kTypeInterrupt: return EndpointType::interrupt;
      default: return EndpointType::control;
    }
  }
  std::uint16_t max_packet(std::uint8_t number) const { return model_.rx_allocation(number); }
  bool stalled(std::uint8_t number) const { return stat_tx(number) == Epr::kStatStall; }
  bool out_armed(std::uint8_t number) const {
    return Epr::STAT_RX.decode(model_.epr(number)) == Epr::kStatValid;
  }
  bool in_pending(std::uint8_t number) const { return stat_tx(number) == Epr::kStatValid; }
  int toggle_in(std::uint8_t number) const {
    return static_cast<int>(Epr::DTOG_TX.decode(model_.epr(number)));
  }
  int toggle_out(std::uint8_t number) const {
    return static_cast<int>(Epr::DTOG_RX.decode(model_.epr(number)));
  }
  int opens(std::uint8_t number) const { return hw_.opens[number]; }
  /// What the real peripheral would refuse or the host would see go wrong, as text.
  std::vector<std::string> violations() const {
    std::vector<std::string> v;
    const auto note = [&v](const char* what, std::uint32_t n) {
      if (n != 0) v.push_back(std::string(what) + ": " + std::to_string(n));
    };
    note("peripheral faults", model_.faults().total());
    note("toggle mismatches", model_.toggle_mismatches());
    note("OUT overflows", model_.rx_overflows());
    note("driver refusals", driver_.refusals());
    return v;
  }

 private:
  static Handshake handshake(::palp::stm32::test::Handshake h) {
    switch (h) {
      case ::palp::stm32::test::Handshake::ack: return Handshake::ack;
      case ::palp::stm32::test::Handshake::nak: return Handshake::nak;
      case ::palp::stm32::test::Handshake::stall: return Handshake::stall;
      default: return Handshake::no_answer;
    }
  }
  std::uint32_t stat_tx(std::uint8_t number) const {
    return Epr::STAT_TX.decode(model_.epr(number));
  }
  // The endpoints whose toggles a request resets (usb-dfu-facts.md §1.2, §1.11).
  void note_toggle_resets(const SetupPacket& s) {
    toggle_resets_.clear();
    if (s.bmRequestType == 0x00 && s.bRequest == 0x09) toggle_resets_ = {1, 2};
    if (s.bmRequestType == 0x01 && s.bRequest == 0x0B)
      toggle_resets_ = {static_cast<std::uint8_t>(s.wIndex == 0 ? 1 : 2)};
    if (s.bmRequestType == 0x02 && s.bRequest == 0x01 && s.wValue == 0)
      toggle_resets_ = {static_cast<std::uint8_t>(s.wIndex & 0x0F)};
  }

  FsdevModel model_;
  FsdevDriver driver_{model_};
  FsdevHardware hw_{driver_};
  std::vector<std::uint8_t> toggle_resets_;
};

}  // namespace palp::usb::test
