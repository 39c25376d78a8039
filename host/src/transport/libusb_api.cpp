// SPDX-License-Identifier: Apache-2.0
// The real UsbApi (usb_api.hpp): each call is the libusb call of the same name, nothing more.
#include <libusb.h>

#include <utility>

#include "transport/usb_api.hpp"

namespace palp::detail {

constexpr bool same(int ours, int libusb) { return ours == libusb; }
static_assert(same(kUsbSuccess, LIBUSB_SUCCESS) &&
              same(kUsbErrorIo, LIBUSB_ERROR_IO) &&
              same(kUsbErrorInvalidParam, LIBUSB_ERROR_INVALID_PARAM) &&
              same(kUsbErrorAccess, LIBUSB_ERROR_ACCESS) &&
              same(kUsbErrorNoDevice, LIBUSB_ERROR_NO_DEVICE) &&
              same(kUsbErrorNotFound, LIBUSB_ERROR_NOT_FOUND) &&
              same(kUsbErrorBusy, LIBUSB_ERROR_BUSY) &&
              same(kUsbErrorTimeout, LIBUSB_ERROR_TIMEOUT) &&
              same(kUsbErrorOverflow, LIBUSB_ERROR_OVERFLOW) &&
              same(kUsbErrorPipe, LIBUSB_ERROR_PIPE) &&
              same(kUsbErrorInterrupted, LIBUSB_ERROR_INTERRUPTED) &&
              same(kUsbErrorNoMem, LIBUSB_ERROR_NO_MEM) &&
              same(kUsbErrorNotSupported, LIBUSB_ERROR_NOT_SUPPORTED) &&
              same(kUsbErrorOther, LIBUSB_ERROR_OTHER),
              "UsbError must have libusb's values");

std::string usb_error_name(int code) {
  switch (code) {
    case kUsbSuccess:
    case kUsbErrorIo:
    case kUsbErrorInvalidParam:
    case kUsbErrorAccess:
    case kUsbErrorNoDevice:
    case kUsbErrorNotFound:
    case kUsbErrorBusy:
    case kUsbErrorTimeout:
    case kUsbErrorOverflow:
    case kUsbErrorPipe:
    case kUsbErrorInterrupted:
    case kUsbErrorNoMem:
    case kUsbErrorNotSupported:
    case kUsbErrorOther: return libusb_error_name(code);
    default: return "LIBUSB_ERROR_" + std::to_string(code);
  }
}

namespace {

libusb_device* dev(UsbDevice d) {
  return reinterpret_cast<libusb_device*>(static_cast<std::uintptr_t>(d));
}
libusb_device_handle* hnd(UsbHandle h) {
  return reinterpret_cast<libusb_device_handle*>(static_cast<std::uintptr_t>(h));
}

class LibusbApi final : public UsbApi {
 public:
  ~LibusbApi() override {
    free_device_list();
    exit();
  }

  int init() override {
    if (ctx_ != nullptr) return LIBUSB_SUCCESS;
    return libusb_init(&ctx_);
  }

  void exit() override {
    free_device_list();
    if (ctx_ != nullptr) libusb_exit(ctx_);
    ctx_ = nullptr;
  }

  int get_device_list(std::vector<UsbDevice>& devices) override {
    free_device_list();
    devices.clear();
    const ssize_t n = libusb_get_device_list(ctx_, &list_);
    if (n < 0) {
      list_ = nullptr;
      return static_cast<int>(n);
    }
    for (ssize_t k = 0; k < n; ++k)
      devices.push_back(static_cast<UsbDevice>(reinterpret_cast<std::uintptr_t>(list_[k])));
    return static_cast<int>(n);
  }

  void free_device_list() override {
    if (list_ != nullptr) libusb_free_device_list(list_, 1);
    list_ = nullptr;
  }

  int get_device_descriptor(UsbDevice device, UsbDeviceDescriptor& out) override {
    libusb_device_descriptor d{};
    const int r = libusb_get_device_descriptor(dev(device), &d);
    if (r < 0) return r;
    out.vid = d.idVendor;
    out.pid = d.idProduct;
    out.bcd_device = d.bcdDevice;
    out.i_product = d.iProduct;
    out.i_serial = d.iSerialNumber;
    return LIBUSB_SUCCESS;
  }

  int open(UsbDevice device, UsbHandle& out) override {
    libusb_device_handle* h = nullptr;
    const int r = libusb_open(dev(device), &h);
    if (r < 0) return r;
    out = static_cast<UsbHandle>(reinterpret_cast<std::uintptr_t>(h));
    return LIBUSB_SUCCESS;
  }

  void close(UsbHandle handle) override { libusb_close(hnd(handle)); }

  int get_string_descriptor_ascii(UsbHandle handle, std::uint8_t index,
                                  std::string& out) override {
    unsigned char buf[256];
    const int n = libusb_get_string_descriptor_ascii(hnd(handle), index, buf, sizeof buf);
    if (n < 0) return n;
    out.assign(reinterpret_cast<const char*>(buf), static_cast<std::size_t>(n));
    return n;
  }

  int kernel_driver_active(UsbHandle handle, int interface) override {
    return libusb_kernel_driver_active(hnd(handle), interface);
  }
  int detach_kernel_driver(UsbHandle handle, int interface) override {
    return libusb_detach_kernel_driver(hnd(handle), interface);
  }
  int claim_interface(UsbHandle handle, int interface) override {
    return libusb_claim_interface(hnd(handle), interface);
  }
  int release_interface(UsbHandle handle, int interface) override {
    return libusb_release_interface(hnd(handle), interface);
  }

  int bulk_transfer(UsbHandle handle, std::uint8_t endpoint, std::uint8_t* data, int length,
                    int& transferred, unsigned timeout_ms) override {
    transferred = 0;
    return libusb_bulk_transfer(hnd(handle), endpoint, data, length, &transferred, timeout_ms);
  }

  int get_active_config_interfaces(UsbDevice device, std::vector<UsbAltSetting>& out) override {
    out.clear();
    libusb_config_descriptor* config = nullptr;
    const int r = libusb_get_active_config_descriptor(dev(device), &config);
    if (r < 0) return r;
    for (int i = 0; i < config->bNumInterfaces; ++i) {
      const libusb_interface& itf = config->interface[i];
      for (int a = 0; a < itf.num_altsetting; ++a) {
        const libusb_interface_descriptor& d = itf.altsetting[a];
        UsbAltSetting s;
        s.interface_number = d.bInterfaceNumber;
        s.alt_setting = d.bAlternateSetting;
        s.interface_class = d.bInterfaceClass;
        s.interface_subclass = d.bInterfaceSubClass;
        s.interface_protocol = d.bInterfaceProtocol;
        s.i_interface = d.iInterface;
        if (d.extra != nullptr && d.extra_length > 0)
          s.extra.assign(d.extra, d.extra + d.extra_length);
        out.push_back(std::move(s));
      }
    }
    libusb_free_config_descriptor(config);
    return LIBUSB_SUCCESS;
  }

  int set_interface_alt_setting(UsbHandle handle, int interface, int alt) override {
    return libusb_set_interface_alt_setting(hnd(handle), interface, alt);
  }

  int control_transfer(UsbHandle handle, std::uint8_t request_type, std::uint8_t request,
                       std::uint16_t value, std::uint16_t index, std::uint8_t* data,
                       std::uint16_t length, unsigned timeout_ms) override {
    return libusb_control_transfer(hnd(handle), request_type, request, value, index, data, length,
                                   timeout_ms);
  }

 private:
  libusb_context* ctx_ = nullptr;
  libusb_device** list_ = nullptr;
};

}  // namespace

std::shared_ptr<UsbApi> make_libusb_api() { return std::make_shared<LibusbApi>(); }

}  // namespace palp::detail
