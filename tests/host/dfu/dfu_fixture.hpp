// SPDX-License-Identifier: Apache-2.0
// The client's tests' common rig: a DfuBus (the ROM bootloader model) and a DfuseDevice opened on
// it with virtual time (the client's sleeps advance the model's clock).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "dfu_device_model.hpp"
#include "palp/dfu.hpp"

namespace palp::dfutest {

using dfumodel::DfuRom;
using dfumodel::DfuState;
using dfumodel::DfuStatus;
using dfu::DfuseError;

inline constexpr std::uint32_t kBase = 0x08000000;         ///< the flash and the image
inline constexpr std::uint32_t kCalibration = 0x0807F000;  ///< the calibration pages (2 x 2 KB)

/// A recognisable image: byte k is a mix of k, never all 0xFF in a row.
inline std::vector<std::uint8_t> test_image(std::size_t size) {
  std::vector<std::uint8_t> v(size);
  for (std::size_t k = 0; k < size; ++k) v[k] = static_cast<std::uint8_t>((k * 7 + k / 251) ^ 0x5A);
  return v;
}

class DfuRig : public ::testing::Test {
 protected:
  std::shared_ptr<dfumodel::DfuBus> bus = std::make_shared<dfumodel::DfuBus>();
  DfuRom& rom = bus->rom;
  std::uint64_t slept_ms = 0;
  std::vector<dfu::Progress> progress;

  dfu::DfuseOptions options() {
    dfu::DfuseOptions o;
    o.sleep = [this](std::chrono::milliseconds d) {
      slept_ms += static_cast<std::uint64_t>(d.count());
      rom.advance(static_cast<std::uint64_t>(d.count()));
    };
    return o;
  }
  dfu::DfuseDevice open(std::chrono::milliseconds wait = std::chrono::milliseconds{0}) {
    return dfu::DfuseDevice::open(bus, {}, wait, options());
  }
  dfu::ProgressFn record() {
    return [this](const dfu::Progress& p) { progress.push_back(p); };
  }
};

/// The DfuseError f throws (fails the test when it throws nothing or something else).
template <class F>
dfu::DfuseError error_of(F&& f) {
  try {
    f();
  } catch (const dfu::DfuseError& e) {
    return e;
  }
  ADD_FAILURE() << "no DfuseError thrown";
  return dfu::DfuseError(dfu::DfuseError::Kind::usb, "(none)");
}

}  // namespace palp::dfutest
