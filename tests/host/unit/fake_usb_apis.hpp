// SPDX-License-Identifier: Apache-2.0
// Fakes of the libusb and hidapi seams (transport/usb_api.hpp, transport/hid_api.hpp) for the
// usb://, hid:// and discovery tests: devices are described by the test, every call is recorded
// with its arguments, and every transfer or report with its bytes.
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "transport/hid_api.hpp"
#include "transport/usb_api.hpp"

namespace palp::fakes {

class FakeUsb final : public detail::UsbApi {
 public:
  struct Device {
    detail::UsbDeviceDescriptor desc;
    std::string serial, product;
    int open_error = 0;    ///< what open() returns (0: success)
    bool kernel_driver = false;
  };
  /// One control transfer as handed to libusb.
  struct Control {
    std::uint8_t request_type, request;
    std::uint16_t value, index, length;
    unsigned timeout_ms;
    std::vector<std::uint8_t> bytes;  ///< OUT: the bytes sent
  };
  /// One bulk transfer as handed to libusb.
  struct Transfer {
    std::uint8_t endpoint;
    int length;
    unsigned timeout_ms;
    std::vector<std::uint8_t> bytes;  ///< OUT: the bytes sent
  };
  /// What the next IN transfer returns: a result code and the bytes that arrive.
  struct In {
    int result;
    std::vector<std::uint8_t> bytes;
  };
  /// What the next OUT transfer returns: a result code and how many bytes it took (-1: all).
  struct Out {
    int result;
    int taken = -1;
  };

  std::vector<Device> devices;
  int init_result = 0;
  int claim_result = 0;
  std::deque<In> in;    ///< empty: an IN transfer times out with no bytes
  std::deque<Out> out;  ///< empty: an OUT transfer takes every byte
  /// What the next control transfer returns (OUT: only its result; IN: its bytes, or its
  /// result when negative); empty: a STALL. The DFU model (tests/host/dfu) plays a whole device.
  std::deque<In> control_in;
  std::vector<Control> controls;
  std::vector<detail::UsbAltSetting> interfaces;  ///< every device's active configuration
  std::vector<std::string> calls;
  std::vector<Transfer> transfers;

  static detail::UsbDeviceDescriptor desc(std::uint16_t bcd = 0x0102, std::uint16_t vid = 0x1209,
                                          std::uint16_t pid = 0x0001) {
    return {vid, pid, bcd, 2, 3};
  }

  int init() override {
    calls.push_back("init");
    return init_result;
  }
  void exit() override { calls.push_back("exit"); }
  int get_device_list(std::vector<detail::UsbDevice>& list) override {
    calls.push_back("get_device_list");
    list.clear();
    for (std::size_t k = 0; k < devices.size(); ++k)
      list.push_back(static_cast<detail::UsbDevice>(100 + k));
    return static_cast<int>(list.size());
  }
  void free_device_list() override { calls.push_back("free_device_list"); }
  int get_device_descriptor(detail::UsbDevice d, detail::UsbDeviceDescriptor& o) override {
    o = dev(d).desc;
    return 0;
  }
  int open(detail::UsbDevice d, detail::UsbHandle& h) override {
    const std::size_t k = static_cast<std::size_t>(d) - 100;
    calls.push_back("open " + std::to_string(k));
    if (devices[k].open_error != 0) return devices[k].open_error;
    h = static_cast<detail::UsbHandle>(k + 1);
    return 0;
  }
  void close(detail::UsbHandle h) override { calls.push_back("close " + idx(h)); }
  int get_string_descriptor_ascii(detail::UsbHandle h, std::uint8_t index,
                                  std::string& o) override {
    const Device& d = devices[static_cast<std::size_t>(h) - 1];
    o = index == d.desc.i_serial ? d.serial : index == d.desc.i_product ? d.product : "";
    return static_cast<int>(o.size());
  }
  int kernel_driver_active(detail::UsbHandle h, int i) override {
    calls.push_back("kernel_driver_active " + idx(h) + " " + std::to_string(i));
    return devices[static_cast<std::size_t>(h) - 1].kernel_driver ? 1 : 0;
  }
  int detach_kernel_driver(detail::UsbHandle h, int i) override {
    calls.push_back("detach_kernel_driver " + idx(h) + " " + std::to_string(i));
    return 0;
  }
  int claim_interface(detail::UsbHandle h, int i) override {
    calls.push_back("claim_interface " + idx(h) + " " + std::to_string(i));
    return claim_result;
  }
  int release_interface(detail::UsbHandle h, int i) override {
    calls.push_back("release_interface " + idx(h) + " " + std::to_string(i));
    return 0;
  }
  int bulk_transfer(detail::UsbHandle, std::uint8_t ep, std::uint8_t* data, int length,
                    int& transferred, unsigned timeout_ms) override {
    Transfer t{ep, length, timeout_ms, {}};
    transferred = 0;
    if ((ep & 0x80) == 0) {
      t.bytes.assign(data, data + length);
      transfers.push_back(t);
      if (out.empty()) {
        transferred = length;
        return 0;
      }
      const Out o = out.front();
      out.pop_front();
      transferred = o.taken < 0 ? length : o.taken;
      return o.result;
    }
    transfers.push_back(t);
    if (in.empty()) return detail::kUsbErrorTimeout;
    const In i = in.front();
    in.pop_front();
    const int n = std::min(length, static_cast<int>(i.bytes.size()));
    std::copy(i.bytes.begin(), i.bytes.begin() + n, data);
    transferred = n;
    return i.result;
  }
  int get_active_config_interfaces(detail::UsbDevice,
                                   std::vector<detail::UsbAltSetting>& o) override {
    o = interfaces;
    return 0;
  }
  int set_interface_alt_setting(detail::UsbHandle h, int i, int alt) override {
    calls.push_back("set_interface_alt_setting " + idx(h) + " " + std::to_string(i) + " " +
                    std::to_string(alt));
    return 0;
  }
  int control_transfer(detail::UsbHandle, std::uint8_t type, std::uint8_t request,
                       std::uint16_t value, std::uint16_t index, std::uint8_t* data,
                       std::uint16_t length, unsigned timeout_ms) override {
    Control c{type, request, value, index, length, timeout_ms, {}};
    if ((type & 0x80) == 0 && data != nullptr) c.bytes.assign(data, data + length);
    controls.push_back(c);
    if (control_in.empty()) return detail::kUsbErrorPipe;
    if ((type & 0x80) == 0) {
      const int r = control_in.front().result;
      control_in.pop_front();
      return r;
    }
    return take(control_in, data, length);
  }

 private:
  static int take(std::deque<In>& queue, std::uint8_t* data, int length) {
    const In i = queue.front();
    queue.pop_front();
    const int n = std::min(length, static_cast<int>(i.bytes.size()));
    std::copy(i.bytes.begin(), i.bytes.begin() + n, data);
    return i.result < 0 ? i.result : n;
  }
  Device& dev(detail::UsbDevice d) { return devices[static_cast<std::size_t>(d) - 100]; }
  static std::string idx(detail::UsbHandle h) {
    return std::to_string(static_cast<std::size_t>(h) - 1);
  }
};

class FakeHid final : public detail::HidApi {
 public:
  std::vector<detail::HidDeviceInfo> devices;
  std::string open_error;  ///< non-empty: open() fails with this error text
  int write_result = 65;
  std::string device_error = "hid_read_timeout: unexpected poll error (device disconnected)";
  /// What the next read_timeout returns: a result and the report bytes. Empty: 0 (timeout).
  std::deque<std::pair<int, std::vector<std::uint8_t>>> reports;
  std::vector<std::string> calls;
  std::vector<std::vector<std::uint8_t>> written;  ///< every hid_write's bytes
  std::vector<std::pair<std::size_t, int>> reads;  ///< every read's length and timeout

  static detail::HidDeviceInfo info(const std::string& serial, std::uint16_t bcd = 0x0102) {
    return {"/dev/hidraw" + std::to_string(serial.size()), 0x1209, 0x0001, serial, bcd,
            "palp probe controller", 1};
  }

  std::vector<detail::HidDeviceInfo> enumerate(std::uint16_t vid, std::uint16_t pid) override {
    calls.push_back("enumerate " + std::to_string(vid) + " " + std::to_string(pid));
    return devices;
  }
  bool open(std::uint16_t, std::uint16_t, const std::string& serial,
            detail::HidHandle& h) override {
    calls.push_back("open " + serial);
    if (!open_error.empty()) return false;
    h = static_cast<detail::HidHandle>(7);
    return true;
  }
  void close(detail::HidHandle) override { calls.push_back("close"); }
  int write(detail::HidHandle, const std::uint8_t* data, std::size_t length) override {
    written.emplace_back(data, data + length);
    return write_result;
  }
  int read_timeout(detail::HidHandle, std::uint8_t* data, std::size_t length,
                   int timeout_ms) override {
    reads.emplace_back(length, timeout_ms);
    if (reports.empty()) return 0;
    const auto r = reports.front();
    reports.pop_front();
    std::copy(r.second.begin(), r.second.end(), data);
    return r.first;
  }
  std::string error(const detail::HidHandle* h) override {
    return h == nullptr ? open_error : device_error;
  }
};

}  // namespace palp::fakes
