// SPDX-License-Identifier: Apache-2.0
// libusb and hidapi as the SDK calls them (its own seams, host/src/transport/usb_api.hpp and
// hid_api.hpp, interfaces unchanged), answered by the board on the rig's bus (board_rig.hpp):
// the SDK's usb:// and hid:// transports and its discovery run unmodified against the device
// stack and the firmware core.
//
// What each call does on the bus, as libusb and Linux's hidraw would:
//   RigUsbApi   one device on the bus; get_device_descriptor: the descriptor read at
//               enumeration; get_string_descriptor_ascii: GET_DESCRIPTOR(string, index, 0x0409)
//               on ep0, UTF-16LE to ASCII with '?' for anything else (libusb's rule);
//               bulk_transfer: the packets of one transfer on the endpoint, NAKs waited out
//               until the timeout (then LIBUSB_ERROR_TIMEOUT with what moved), STALL ->
//               LIBUSB_ERROR_PIPE, a packet that overflows the buffer -> LIBUSB_ERROR_OVERFLOW.
//               A transfer on an endpoint whose interface is not claimed fails
//               LIBUSB_ERROR_NOT_FOUND here (usbfs would claim it implicitly, with a kernel
//               warning): a test sees an SDK that forgot to claim.
//   RigHidApi   enumerate: the board's HID interface with the serial, product and bcdDevice
//               its descriptors serve (read on ep0, as the kernel caches them); write: report
//               ID 0 and one 64-byte interrupt OUT report (hidraw), bounded at 5 s as the kernel
//               bounds it; read_timeout: one interrupt IN report or 0 at the timeout.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "board_rig.hpp"
#include "transport/hid_api.hpp"
#include "transport/usb_api.hpp"

namespace palp::usb_e2e {

/// The string descriptor `index` as libusb_get_string_descriptor_ascii gives it; false when
/// the device STALLs it or the reply is not a string descriptor.
bool read_string_ascii(BoardRig& rig, std::uint8_t index, std::string& out);

class RigUsbApi final : public detail::UsbApi {
 public:
  explicit RigUsbApi(std::shared_ptr<BoardRig> rig) : rig_(std::move(rig)) {}

  int init() override { return detail::kUsbSuccess; }
  void exit() override {}
  int get_device_list(std::vector<detail::UsbDevice>& devices) override;
  void free_device_list() override {}
  int get_device_descriptor(detail::UsbDevice device, detail::UsbDeviceDescriptor& out) override;
  int open(detail::UsbDevice device, detail::UsbHandle& out) override;
  void close(detail::UsbHandle handle) override;
  int get_string_descriptor_ascii(detail::UsbHandle handle, std::uint8_t index,
                                  std::string& out) override;
  int kernel_driver_active(detail::UsbHandle, int) override { return 0; }
  int detach_kernel_driver(detail::UsbHandle, int) override { return detail::kUsbErrorNotFound; }
  int claim_interface(detail::UsbHandle handle, int interface) override;
  int release_interface(detail::UsbHandle handle, int interface) override;
  int bulk_transfer(detail::UsbHandle handle, std::uint8_t endpoint, std::uint8_t* data,
                    int length, int& transferred, unsigned timeout_ms) override;

 private:
  std::shared_ptr<BoardRig> rig_;
  bool open_ = false;
  int claimed_ = -1;  // the claimed interface (-1: none)
};

class RigHidApi final : public detail::HidApi {
 public:
  explicit RigHidApi(std::shared_ptr<BoardRig> rig) : rig_(std::move(rig)) {}

  std::vector<detail::HidDeviceInfo> enumerate(std::uint16_t vid, std::uint16_t pid) override;
  bool open(std::uint16_t vid, std::uint16_t pid, const std::string& serial,
            detail::HidHandle& out) override;
  void close(detail::HidHandle handle) override;
  int write(detail::HidHandle handle, const std::uint8_t* data, std::size_t length) override;
  int read_timeout(detail::HidHandle handle, std::uint8_t* data, std::size_t length,
                   int timeout_ms) override;
  std::string error(const detail::HidHandle*) override { return error_; }

 private:
  std::shared_ptr<BoardRig> rig_;
  bool open_ = false;
  std::string error_;
};

}  // namespace palp::usb_e2e
