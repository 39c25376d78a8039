// SPDX-License-Identifier: Apache-2.0
// The USB driver (usb_fsdev.hpp) on the peripheral model (fsdev_model.hpp), initialised,
// attached and bus-reset as a host would leave it before its first SETUP; every test ends by
// checking the model saw no access the real peripheral would refuse and no toggle mismatch.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fsdev_model.hpp"
#include "usb_fsdev.hpp"

namespace palp::stm32::test {

using fsdev::UsbFsdev;
using ::palp::usb::EndpointType;
using ::palp::usb::Event;
using ::palp::usb::EventKind;

/// An event as text ("setup 0", "none"), so a failed comparison reads plainly.
inline std::string describe(const Event& e) {
  static constexpr const char* kNames[] = {"none",        "reset",   "setup", "out",
                                           "in_complete", "suspend", "resume"};
  const std::string name = kNames[static_cast<int>(e.kind)];
  return e.kind == EventKind::none ? name : name + " " + std::to_string(e.endpoint);
}

class UsbFsdevTest : public ::testing::Test {
 protected:
  void SetUp() override {
    driver.init();
    driver.connect(true);
    model.bus_reset();
    ASSERT_EQ(describe(driver.poll()), "reset 0");
    ASSERT_EQ(describe(driver.poll()), "none");
  }

  void TearDown() override {
    EXPECT_EQ(model.faults().total(), 0u);
    EXPECT_EQ(model.toggle_mismatches(), 0u);
    EXPECT_EQ(model.rx_overflows(), 0u);
    EXPECT_EQ(driver.refusals(), expected_refusals);
  }

  /// Every pending event, in order (at most 16), as describe() text.
  std::vector<std::string> drain() {
    std::vector<std::string> events;
    for (int i = 0; i < 16; ++i) {
      const Event e = driver.poll();
      if (e.kind == EventKind::none) {
        break;
      }
      events.push_back(describe(e));
    }
    return events;
  }

  FsdevModel model;
  UsbFsdev<FsdevModel> driver{model};
  std::uint32_t expected_refusals = 0;
};

/// `size` bytes 0, 1, 2 … offset by `seed` (mod 256): a pattern a wrong offset or stride breaks.
inline std::vector<std::uint8_t> pattern(std::size_t size, unsigned seed) {
  std::vector<std::uint8_t> bytes(size);
  for (std::size_t i = 0; i < size; ++i) {
    bytes[i] = static_cast<std::uint8_t>((i * 7 + seed) & 0xFF);
  }
  return bytes;
}

}  // namespace palp::stm32::test
