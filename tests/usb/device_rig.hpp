// SPDX-License-Identifier: Apache-2.0
// A Device over a bus's hardware with its host (host.hpp), and the steps most tests start from:
// attach, enumerate to the Configured state at address 5. Bus is PacketBus (packet_bus.hpp, the
// contract at the packet level) or FsdevBus (fsdev_bus.hpp, the FSDEV driver on the register
// model, when the tree has it): the typed tests run on every bus in Buses.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "host.hpp"
#include "packet_bus.hpp"
#include "palp/usb/device.hpp"
#ifdef PALP_USB_TESTS_FSDEV
#include "fsdev_bus.hpp"
#endif

namespace palp::usb::test {

template <class Bus, std::size_t Rx = 1024, std::size_t Tx = 2048>
struct Rig {
  Bus bus;
  Device<typename Bus::Hardware, Rx, Tx> device{bus.hardware()};
  Host<Bus> host{bus, [this] { device.service(); }};

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

#ifdef PALP_USB_TESTS_FSDEV
using Buses = ::testing::Types<PacketBus, FsdevBus>;
#else
using Buses = ::testing::Types<PacketBus>;
#endif

/// Names the typed tests' instances by their bus.
struct BusName {
  template <class Bus>
  static std::string GetName(int) {
    return std::is_same_v<Bus, PacketBus> ? "PacketBus" : "Fsdev";
  }
};

}  // namespace palp::usb::test
