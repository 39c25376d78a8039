// SPDX-License-Identifier: Apache-2.0
// The DFU requests on one claimed interface (dfu_session.hpp; usb-dfu-facts.md §5.2-§5.6).
#include "dfu/dfu_session.hpp"

#include <algorithm>
#include <thread>

#include "dfu/dfu_messages.hpp"

namespace palp::dfu::internal {

namespace {

constexpr std::uint8_t kRequestOut = 0x21;  // OUT, class, interface (facts §5.2)
constexpr std::uint8_t kRequestIn = 0xA1;   // IN, class, interface
constexpr int kStatusStallsTolerated = 3;   // of GETSTATUS while busy (dfu-util, facts §5.5)
constexpr const char* kBootloaderHint =
    "to reach the bootloader again, hold BOOT0 high while resetting the board";

std::uint8_t to_u8(State s) { return static_cast<std::uint8_t>(s); }
std::uint8_t to_u8(Status s) { return static_cast<std::uint8_t>(s); }

std::string reported(const StatusReply& s) {
  return status_name(s.status) + " in " + state_name(s.state) + " (" + status_meaning(s.status) +
         ")";
}

}  // namespace

Session::Session(std::shared_ptr<detail::UsbApi> usb, detail::UsbHandle handle, int interface,
                 DfuseOptions options)
    : usb_(std::move(usb)), handle_(handle), interface_(interface), options_(std::move(options)) {}

void sleep_for(const DfuseOptions& options, std::chrono::milliseconds d) {
  if (options.sleep) options.sleep(d);
  else std::this_thread::sleep_for(d);
}

int Session::control(bool in, Request request, std::uint16_t value, std::uint8_t* data,
                     std::uint16_t length) {
  const auto ms = std::max<std::chrono::milliseconds::rep>(options_.control_timeout.count(), 1);
  return usb_->control_transfer(handle_, in ? kRequestIn : kRequestOut, request, value,
                                static_cast<std::uint16_t>(interface_), data, length,
                                static_cast<unsigned>(ms));
}

namespace {
int raw_status(Session& s, StatusReply& out) {
  std::uint8_t b[6] = {};
  const int r = s.control(true, kGetStatus, 0, b, sizeof b);
  if (r < 0) return r;
  if (r != 6) return -1000 - r;  // a short reply: reported by get_status
  out.status = b[0];
  out.poll_timeout_ms = b[1] | (b[2] << 8) | (b[3] << 16);
  out.state = b[4];
  return 0;
}
}  // namespace

StatusReply Session::get_status(const Doing& doing) {
  StatusReply s;
  fail_status_read(raw_status(*this, s), doing);
  return s;
}

void Session::fail_status_read(int r, const Doing& doing) {
  if (r <= -1000)
    throw DfuseError(DfuseError::Kind::protocol,
                     doing.what + " failed: the device's GETSTATUS reply has " +
                         std::to_string(-1000 - r) + " bytes, not 6; unplug it and put it back in "
                         "DFU mode (" + kBootloaderHint + ")",
                     doing.address);
  if (r < 0) fail_transfer(r, doing);
}

void Session::abort(const Doing& doing) {
  if (const int r = control(false, kAbort, 0, nullptr, 0); r < 0) fail_transfer(r, doing);
}

void Session::clear_status(const Doing& doing) {
  if (const int r = control(false, kClrStatus, 0, nullptr, 0); r < 0) fail_transfer(r, doing);
}

void Session::to_idle(const Doing& doing) {
  StatusReply s = get_status(doing);
  if (s.state == to_u8(State::dfu_idle)) return;
  if (s.state == to_u8(State::app_idle) || s.state == to_u8(State::app_detach))
    throw DfuseError(DfuseError::Kind::protocol,
                     doing.what + " failed: the device is in " + state_name(s.state) +
                         ", i.e. running an application, not the DFU bootloader; " +
                         kBootloaderHint,
                     doing.address, s.state, s.status);
  if (s.state == to_u8(State::error)) clear_status(doing);
  else abort(doing);
  s = get_status(doing);
  if (s.state != to_u8(State::dfu_idle))
    throw DfuseError(DfuseError::Kind::protocol,
                     doing.what + " failed: the device stays in " + state_name(s.state) + " (" +
                         status_name(s.status) + ") after " +
                         (s.state == to_u8(State::error) ? "CLRSTATUS" : "ABORT") +
                         " instead of going to dfuIDLE; unplug it and put it back in DFU mode (" +
                         kBootloaderHint + ")",
                     doing.address, s.state, s.status);
}

std::string Session::recover() {
  StatusReply s;
  int r = raw_status(*this, s);
  if (r == detail::kUsbErrorNoDevice) return "The device is gone (LIBUSB_ERROR_NO_DEVICE)";
  if (r < 0)
    return "Its state could not be read (" +
           (r <= -1000 ? "a short GETSTATUS reply" : detail::usb_error_name(r)) +
           "): unplug it and put it back in DFU mode (" + kBootloaderHint + ")";
  if (s.state == to_u8(State::dfu_idle)) return "The device is in dfuIDLE";
  const bool was_error = s.state == to_u8(State::error);
  r = control(false, was_error ? kClrStatus : kAbort, 0, nullptr, 0);
  StatusReply after;
  if (r >= 0) r = raw_status(*this, after);
  if (r >= 0 && after.state == to_u8(State::dfu_idle))
    return was_error ? "The error was cleared (CLRSTATUS): the device is in dfuIDLE"
                     : "Aborted (ABORT): the device is in dfuIDLE";
  return std::string("The device did not return to dfuIDLE (") +
         (r < 0 ? (r <= -1000 ? std::string("a short GETSTATUS reply") : detail::usb_error_name(r))
                : state_name(after.state) + ", " + status_name(after.status)) +
         "): unplug it and put it back in DFU mode (" + kBootloaderHint + ")";
}

void Session::fail_transfer(int r, const Doing& doing) {
  const std::string name = detail::usb_error_name(r);
  if (r == detail::kUsbErrorNoDevice)
    throw DfuseError(DfuseError::Kind::unplugged,
                     doing.what + " failed: the device was unplugged (" + name +
                         "). Plug it back in (" + kBootloaderHint + "). " + doing.advice,
                     doing.address, std::nullopt, std::nullopt, r);
  if (r == detail::kUsbErrorPipe) {
    StatusReply s;
    const int rs = raw_status(*this, s);
    std::string cause = "the device stalled the request (" + name + ")";
    std::optional<std::uint8_t> state, status;
    if (rs == 0) {
      cause += " and reports " + reported(s);
      state = s.state;
      status = s.status;
    }
    throw DfuseError(DfuseError::Kind::stalled,
                     doing.what + " failed: " + cause + ". " + recover() + ". " + doing.advice,
                     doing.address, state, status, r);
  }
  if (r == detail::kUsbErrorTimeout)
    throw DfuseError(DfuseError::Kind::timeout,
                     doing.what + " failed: no answer within " +
                         std::to_string(options_.control_timeout.count()) + " ms (" + name +
                         "). " + recover() + ". " + doing.advice,
                     doing.address, std::nullopt, std::nullopt, r);
  throw DfuseError(DfuseError::Kind::usb,
                   doing.what + " failed: " + name + ". " + recover() + ". " + doing.advice,
                   doing.address, std::nullopt, std::nullopt, r);
}

void Session::fail_status(const StatusReply& s, const Doing& doing) {
  throw DfuseError(DfuseError::Kind::device_status,
                   doing.what + " failed: the device reported " + reported(s) + ". " + recover() +
                       ". " + doing.advice,
                   doing.address, s.state, s.status);
}

void Session::download_block(std::uint16_t block, std::span<const std::uint8_t> bytes,
                             const Doing& doing) {
  std::vector<std::uint8_t> copy(bytes.begin(), bytes.end());  // libusb takes a non-const buffer
  if (const int r = control(false, kDnload, block, copy.empty() ? nullptr : copy.data(),
                            static_cast<std::uint16_t>(copy.size()));
      r < 0)
    fail_transfer(r, doing);
  std::chrono::milliseconds waited{0};
  std::chrono::milliseconds wait{1};  // the last bwPollTimeout (at least 1 ms)
  int stalls = 0;
  for (;;) {
    StatusReply s;
    const int r = raw_status(*this, s);
    if (r == detail::kUsbErrorPipe && stalls < kStatusStallsTolerated) {
      ++stalls;  // some ROMs stall GETSTATUS while they program (facts §5.5): wait, ask again
      sleep_for(options_, wait);
      waited += wait;
      continue;
    }
    if (r != 0) fail_status_read(r, doing);
    if (s.status != to_u8(Status::ok) || s.state == to_u8(State::error)) fail_status(s, doing);
    if (s.state == to_u8(State::dnload_idle)) return;
    if (s.state != to_u8(State::dnbusy) && s.state != to_u8(State::dnload_sync))
      throw DfuseError(DfuseError::Kind::protocol,
                       doing.what + " failed: the device went to " + state_name(s.state) +
                           " instead of dfuDNLOAD-IDLE. " + recover() + ". " + doing.advice,
                       doing.address, s.state, s.status);
    wait = std::chrono::milliseconds{std::max<std::uint32_t>(s.poll_timeout_ms, 1)};
    if (waited + wait > options_.busy_limit)
      throw DfuseError(DfuseError::Kind::timeout,
                       doing.what + " failed: the device stayed busy (" + state_name(s.state) +
                           ") longer than " + std::to_string(options_.busy_limit.count()) +
                           " ms; unplug it and put it back in DFU mode (" + kBootloaderHint +
                           "). " + doing.advice,
                       doing.address, s.state, s.status);
    sleep_for(options_, wait);  // bwPollTimeout: the device is not to be asked again before
    waited += wait;
  }
}

void Session::command(std::span<const std::uint8_t> bytes, const Doing& doing) {
  download_block(0, bytes, doing);
}

void Session::set_address(std::uint32_t address, const Doing& doing) {
  const std::uint8_t cmd[5] = {0x21, static_cast<std::uint8_t>(address),
                               static_cast<std::uint8_t>(address >> 8),
                               static_cast<std::uint8_t>(address >> 16),
                               static_cast<std::uint8_t>(address >> 24)};
  command(cmd, doing);
}

std::size_t Session::upload_block(std::uint16_t block, std::uint8_t* data, std::size_t length,
                                  const Doing& doing) {
  const int r = control(true, kUpload, block, data, static_cast<std::uint16_t>(length));
  if (r < 0) fail_transfer(r, doing);
  return static_cast<std::size_t>(r);
}

}  // namespace palp::dfu::internal
