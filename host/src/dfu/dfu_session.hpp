// SPDX-License-Identifier: Apache-2.0
// Internal to the DfuSe client: the DFU requests on one claimed interface (usb-dfu-facts.md
// §5.2-§5.6), GETSTATUS polling that honours bwPollTimeout, recovery to dfuIDLE, and the
// DfuseError for every failure. dfuse_device.cpp builds the public calls from these.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "palp/dfu.hpp"
#include "transport/usb_api.hpp"

namespace palp::dfu::internal {

/// DFU class requests (facts §5.2).
enum Request : std::uint8_t {
  kDetach = 0, kDnload = 1, kUpload = 2, kGetStatus = 3, kClrStatus = 4, kGetState = 5, kAbort = 6,
};

/// A GETSTATUS reply (facts §5.4).
struct StatusReply {
  std::uint8_t status = 0;
  std::uint32_t poll_timeout_ms = 0;
  std::uint8_t state = 0;
};

/// What a request is part of, for its error message: "erasing the page at 0x08000800", the
/// address concerned, and what the user can do if it fails.
struct Doing {
  std::string what;
  std::optional<std::uint32_t> address;
  std::string advice;
};

/// Waits d through the options' sleep hook (std::this_thread::sleep_for when it is empty).
void sleep_for(const DfuseOptions& options, std::chrono::milliseconds d);

class Session {
 public:
  Session(std::shared_ptr<detail::UsbApi> usb, detail::UsbHandle handle, int interface,
          DfuseOptions options);

  /// DNLOAD(block, bytes) then GETSTATUS polls until the device leaves dfuDNLOAD-SYNC/dfuDNBUSY;
  /// it must end in dfuDNLOAD-IDLE with status OK. Throws DfuseError (after recovering the
  /// device to dfuIDLE when it can).
  void download_block(std::uint16_t block, std::span<const std::uint8_t> bytes, const Doing& doing);
  /// A DfuSe command: DNLOAD block 0 (facts §5.5).
  void command(std::span<const std::uint8_t> bytes, const Doing& doing);
  /// SET_ADDRESS_POINTER (0x21 + address).
  void set_address(std::uint32_t address, const Doing& doing);
  /// UPLOAD(block) of up to length bytes into data; returns the bytes received.
  std::size_t upload_block(std::uint16_t block, std::uint8_t* data, std::size_t length,
                           const Doing& doing);
  /// GETSTATUS; throws on a transfer failure or a reply of the wrong length.
  StatusReply get_status(const Doing& doing);
  /// ABORT (back to dfuIDLE from an idle state).
  void abort(const Doing& doing);
  /// CLRSTATUS (dfuERROR -> dfuIDLE).
  void clear_status(const Doing& doing);
  /// Brings the device to dfuIDLE: CLRSTATUS from dfuERROR, ABORT from any other state, then
  /// GETSTATUS to check. Throws when the device is not in dfuIDLE afterwards.
  void to_idle(const Doing& doing);
  /// The raw control transfer (class, interface); returns libusb's result.
  int control(bool in, Request request, std::uint16_t value, std::uint8_t* data,
              std::uint16_t length);

  /// Throws the DfuseError for a failed transfer (r < 0): unplugged, stalled (after reading the
  /// device's status and recovering), timeout, or other.
  [[noreturn]] void fail_transfer(int r, const Doing& doing);
  /// Throws for a failed GETSTATUS (r < 0: a transfer error, or a reply of the wrong length);
  /// returns for r == 0.
  void fail_status_read(int r, const Doing& doing);
  /// Throws the DfuseError for an error status the device reported, after recovering.
  [[noreturn]] void fail_status(const StatusReply& s, const Doing& doing);

  const DfuseOptions& options() const { return options_; }

 private:
  /// Best effort after a failure: to dfuIDLE; returns the sentence saying where the device is.
  std::string recover();

  std::shared_ptr<detail::UsbApi> usb_;
  detail::UsbHandle handle_;
  int interface_;
  DfuseOptions options_;
};

}  // namespace palp::dfu::internal
