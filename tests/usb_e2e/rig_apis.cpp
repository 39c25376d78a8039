// SPDX-License-Identifier: Apache-2.0
// libusb and hidapi over the rig's bus (rig_apis.hpp).
#include "rig_apis.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "palp/protocol/usb.hpp"

namespace palp::usb_e2e {

namespace {

namespace pu = palp::proto::usb;

constexpr auto kDevice = static_cast<detail::UsbDevice>(1);
constexpr auto kUsbHandle = static_cast<detail::UsbHandle>(1);
constexpr auto kHidHandle = static_cast<detail::HidHandle>(1);
constexpr std::uint16_t kLangEnUs = 0x0409;
/// What the kernel allows one hidraw write (an interrupt OUT report) before it gives up.
constexpr auto kHidWriteBound = std::chrono::seconds(5);

int libusb_result(Transfer t) {
  switch (t) {
    case Transfer::ok: return detail::kUsbSuccess;
    case Transfer::timeout: return detail::kUsbErrorTimeout;
    case Transfer::stall: return detail::kUsbErrorPipe;
    case Transfer::overflow: return detail::kUsbErrorOverflow;
    case Transfer::no_answer: return detail::kUsbErrorIo;
  }
  return detail::kUsbErrorOther;
}

std::uint16_t le16(const std::vector<std::uint8_t>& d, std::size_t at) {
  return static_cast<std::uint16_t>(d[at] | d[at + 1] << 8);
}

}  // namespace

bool read_string_ascii(BoardRig& rig, std::uint8_t index, std::string& out) {
  std::vector<std::uint8_t> d;
  if (!rig.control_in({0x80, 0x06, static_cast<std::uint16_t>(0x0300 | index), kLangEnUs, 255}, d))
    return false;
  if (d.size() < 2 || d[1] != 0x03 || d[0] > d.size() || d[0] % 2 != 0) return false;
  out.clear();
  for (std::size_t k = 2; k + 1 < d[0]; k += 2) {
    const std::uint16_t c = le16(d, k);
    out.push_back(c < 0x80 ? static_cast<char>(c) : '?');
  }
  return true;
}

// ---- libusb ----------------------------------------------------------------------------------

int RigUsbApi::get_device_list(std::vector<detail::UsbDevice>& devices) {
  devices = {kDevice};
  return 1;
}

int RigUsbApi::get_device_descriptor(detail::UsbDevice device, detail::UsbDeviceDescriptor& out) {
  const std::vector<std::uint8_t>& d = rig_->device_descriptor();
  if (device != kDevice || d.size() != 18) return detail::kUsbErrorNoDevice;
  out.vid = le16(d, 8);
  out.pid = le16(d, 10);
  out.bcd_device = le16(d, 12);
  out.i_product = d[15];
  out.i_serial = d[16];
  return detail::kUsbSuccess;
}

int RigUsbApi::open(detail::UsbDevice device, detail::UsbHandle& out) {
  if (device != kDevice) return detail::kUsbErrorNoDevice;
  if (open_) return detail::kUsbErrorBusy;  // one handle at a time is all these tests need
  open_ = true;
  out = kUsbHandle;
  return detail::kUsbSuccess;
}

void RigUsbApi::close(detail::UsbHandle handle) {
  if (handle == kUsbHandle) open_ = false;
}

int RigUsbApi::get_string_descriptor_ascii(detail::UsbHandle handle, std::uint8_t index,
                                           std::string& out) {
  if (handle != kUsbHandle || !open_) return detail::kUsbErrorInvalidParam;
  if (!read_string_ascii(*rig_, index, out)) return detail::kUsbErrorPipe;
  return static_cast<int>(out.size());
}

int RigUsbApi::claim_interface(detail::UsbHandle handle, int interface) {
  if (handle != kUsbHandle || !open_) return detail::kUsbErrorInvalidParam;
  if (interface != pu::kVendorInterface && interface != pu::kHidInterface)
    return detail::kUsbErrorNotFound;
  claimed_ = interface;
  return detail::kUsbSuccess;
}

int RigUsbApi::release_interface(detail::UsbHandle handle, int interface) {
  if (handle != kUsbHandle || claimed_ != interface) return detail::kUsbErrorNotFound;
  claimed_ = -1;
  return detail::kUsbSuccess;
}

int RigUsbApi::bulk_transfer(detail::UsbHandle handle, std::uint8_t endpoint, std::uint8_t* data,
                             int length, int& transferred, unsigned timeout_ms) {
  transferred = 0;
  if (handle != kUsbHandle || !open_ || length < 0) return detail::kUsbErrorInvalidParam;
  const std::uint8_t number = endpoint & 0x0F;
  const int interface = number == (pu::kBulkOutEndpoint & 0x0F) ? pu::kVendorInterface
                                                                 : pu::kHidInterface;
  if (claimed_ != interface) return detail::kUsbErrorNotFound;
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  std::size_t moved = 0;
  const Transfer t =
      (endpoint & 0x80) != 0
          ? rig_->transfer_in(number, data, static_cast<std::size_t>(length), moved, deadline)
          : rig_->transfer_out(number, data, static_cast<std::size_t>(length), moved, deadline);
  transferred = static_cast<int>(moved);
  return libusb_result(t);
}

// ---- hidapi ----------------------------------------------------------------------------------

std::vector<detail::HidDeviceInfo> RigHidApi::enumerate(std::uint16_t vid, std::uint16_t pid) {
  const std::vector<std::uint8_t>& d = rig_->device_descriptor();
  if (le16(d, 8) != vid || le16(d, 10) != pid) return {};
  detail::HidDeviceInfo info;
  info.path = "rig:hidraw0";
  info.vid = vid;
  info.pid = pid;
  info.release_number = le16(d, 12);
  info.interface_number = pu::kHidInterface;
  if (d[16] != 0) read_string_ascii(*rig_, d[16], info.serial);
  if (d[15] != 0) read_string_ascii(*rig_, d[15], info.product);
  return {info};
}

bool RigHidApi::open(std::uint16_t vid, std::uint16_t pid, const std::string& serial,
                     detail::HidHandle& out) {
  const auto found = enumerate(vid, pid);
  if (found.empty() || (!serial.empty() && found.front().serial != serial)) {
    error_ = "hid_open: no such device";
    return false;
  }
  open_ = true;
  out = kHidHandle;
  return true;
}

void RigHidApi::close(detail::HidHandle handle) {
  if (handle == kHidHandle) open_ = false;
}

int RigHidApi::write(detail::HidHandle handle, const std::uint8_t* data, std::size_t length) {
  if (handle != kHidHandle || !open_ || length != 1 + pu::kHidReportSize || data[0] != 0) {
    error_ = "hid_write: not a report of this device (report ID 0, 64 bytes)";
    return -1;
  }
  std::size_t sent = 0;
  const Transfer t = rig_->transfer_out(pu::kHidOutEndpoint & 0x0F, data + 1, pu::kHidReportSize,
                                        sent, Clock::now() + kHidWriteBound);
  if (t != Transfer::ok) {
    error_ = "hid_write: the interrupt OUT report was not taken";
    return -1;
  }
  return static_cast<int>(length);
}

int RigHidApi::read_timeout(detail::HidHandle handle, std::uint8_t* data, std::size_t length,
                            int timeout_ms) {
  if (handle != kHidHandle || !open_) {
    error_ = "hid_read_timeout: not open";
    return -1;
  }
  std::uint8_t report[pu::kHidReportSize];
  std::size_t got = 0;
  const Transfer t = rig_->transfer_in(pu::kHidInEndpoint & 0x0F, report, sizeof report, got,
                                       Clock::now() + std::chrono::milliseconds(timeout_ms),
                                       /*one_packet=*/true);
  if (t == Transfer::timeout) return 0;
  if (t != Transfer::ok) {
    error_ = "hid_read_timeout: the interrupt IN endpoint failed";
    return -1;
  }
  const std::size_t n = std::min(got, length);
  std::memcpy(data, report, n);
  return static_cast<int>(n);
}

}  // namespace palp::usb_e2e
