// SPDX-License-Identifier: Apache-2.0
// The seam between the hid:// transport (and discovery) and hidapi: the hidapi calls the SDK
// makes, behind a small interface, so tests can put a fake in its place and check the exact
// reports the SDK hands to hidapi. It does not include hidapi.h; strings are UTF-8 here (hidapi's
// are wchar_t, converted in hidapi_api.cpp).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "palp/transport.hpp"

namespace palp::detail {

/// An opened HID device (hid_device*), valid until HidApi::close().
enum class HidHandle : std::uintptr_t {};

/// One entry of hid_enumerate().
struct HidDeviceInfo {
  std::string path;
  std::uint16_t vid = 0, pid = 0;
  std::string serial;               ///< serial_number
  std::uint16_t release_number = 0; ///< bcdDevice
  std::string product;              ///< product_string
  int interface_number = -1;
};

/// The hidapi calls the SDK makes.
class HidApi {
 public:
  virtual ~HidApi() = default;

  /// hid_enumerate(vid, pid), the list copied and freed. Empty when there are none (or HID cannot
  /// be enumerated on this machine).
  virtual std::vector<HidDeviceInfo> enumerate(std::uint16_t vid, std::uint16_t pid) = 0;

  /// hid_open(vid, pid, serial) (serial "" = nullptr, the first one). Returns false on failure;
  /// error() then says why.
  virtual bool open(std::uint16_t vid, std::uint16_t pid, const std::string& serial,
                    HidHandle& out) = 0;
  virtual void close(HidHandle handle) = 0;  ///< hid_close

  /// hid_write: data[0] is the report ID (0x00: the interface has none), then the report.
  /// Returns the bytes written or -1. hidapi takes no timeout here (see hid_transport.cpp).
  virtual int write(HidHandle handle, const std::uint8_t* data, std::size_t length) = 0;

  /// hid_read_timeout: one input report (without report ID) into data. Returns its length, 0
  /// when none came within timeout_ms, -1 on error (unplugged).
  virtual int read_timeout(HidHandle handle, std::uint8_t* data, std::size_t length,
                           int timeout_ms) = 0;

  /// hid_error(handle), or hid_error(NULL) after a failed open(): the last error's text.
  virtual std::string error(const HidHandle* handle) = 0;
};

/// The real HidApi over hidapi (hidapi_api.cpp).
std::shared_ptr<HidApi> make_hidapi_api();

/// The hid:// transport over the given HidApi (tests pass a fake). Throws ConnectionError as
/// open_transport() does.
std::unique_ptr<Transport> open_hid_transport(const Uri& uri, std::chrono::milliseconds timeout,
                                              std::shared_ptr<HidApi> api);

}  // namespace palp::detail
