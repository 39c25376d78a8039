// A Device<PacketBus> with its host (host.hpp), and the steps most tests start from: attach,
// enumerate to the Configured state at address 5.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>

#include "host.hpp"
#include "packet_bus.hpp"
#include "palp/usb/device.hpp"

namespace palp::usb::test {

template <std::size_t Rx = 1024, std::size_t Tx = 2048>
struct Rig {
  PacketBus bus;
  Device<PacketBus, Rx, Tx> device{bus};
  Host host{bus, [this] { device.service(); }};

  Rig() {
    device.start();
    host.reset();
  }

  /// SET_ADDRESS(5) then SET_CONFIGURATION(1); asserts both succeed.
  void configure() {
    ASSERT_EQ(host.control_out(set_address(5)).outcome, Outcome::ok);
    host.address = 5;
    ASSERT_EQ(host.control_out(set_configuration(1)).outcome, Outcome::ok);
    ASSERT_TRUE(device.configured());
  }

  /// The app's side: everything received so far.
  std::vector<std::uint8_t> drain() {
    std::vector<std::uint8_t> out;
    std::uint8_t chunk[97];
    for (std::size_t n; (n = device.read(chunk, sizeof chunk)) > 0;)
      out.insert(out.end(), chunk, chunk + n);
    device.service();  // as the board does after link_read: paused OUT endpoints re-arm
    return out;
  }
};

}  // namespace palp::usb::test
