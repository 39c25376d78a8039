// SPDX-License-Identifier: Apache-2.0
// The seam between the usb:// transport (and discovery) and libusb: the handful of libusb calls
// the SDK makes, behind a small interface, so tests can put a fake in its place and check the
// exact bytes, endpoints and timeouts the SDK hands to libusb.
//
// The interface mirrors libusb closely: same call names, same meaning, libusb's error codes
// (UsbError below has libusb's values; libusb_api.cpp checks that at compile time). It does not
// include libusb.h, so tests build without it.
//
// Also here: what the usb:// and hid:// transports share (which identity to look for, how to
// pick one controller by serial number, the messages for it), and the factory for tests.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "palp/discovery.hpp"
#include "palp/transport.hpp"

namespace palp::detail {

/// libusb's error codes (enum libusb_error), same values.
enum UsbError : int {
  kUsbSuccess = 0,
  kUsbErrorIo = -1,
  kUsbErrorInvalidParam = -2,
  kUsbErrorAccess = -3,
  kUsbErrorNoDevice = -4,
  kUsbErrorNotFound = -5,
  kUsbErrorBusy = -6,
  kUsbErrorTimeout = -7,
  kUsbErrorOverflow = -8,
  kUsbErrorPipe = -9,
  kUsbErrorInterrupted = -10,
  kUsbErrorNoMem = -11,
  kUsbErrorNotSupported = -12,
  kUsbErrorOther = -99,
};

/// libusb's name for an error code ("LIBUSB_ERROR_ACCESS"), as libusb_error_name() gives it;
/// "LIBUSB_ERROR_<code>" for a code libusb does not define.
std::string usb_error_name(int code);

/// A device on the bus (libusb_device*), valid until UsbApi::free_device_list().
enum class UsbDevice : std::uintptr_t {};
/// An opened device (libusb_device_handle*), valid until UsbApi::close().
enum class UsbHandle : std::uintptr_t {};

/// The fields of the device descriptor the SDK uses.
struct UsbDeviceDescriptor {
  std::uint16_t vid = 0, pid = 0;
  std::uint16_t bcd_device = 0;  ///< firmware version, palp::proto::usb::bcd_device()
  std::uint8_t i_product = 0, i_serial = 0;  ///< string descriptor indices (0 = none)
};

/// One alternate setting of an interface of the active configuration
/// (libusb_interface_descriptor): what the DfuSe client (host/src/dfu) reads of it.
struct UsbAltSetting {
  std::uint8_t interface_number = 0, alt_setting = 0;
  std::uint8_t interface_class = 0, interface_subclass = 0, interface_protocol = 0;
  std::uint8_t i_interface = 0;  ///< string index of its name (DfuSe: the memory-layout string)
  /// The class-specific descriptors that follow it in the configuration (libusb's `extra`),
  /// e.g. the DFU functional descriptor (usb-dfu-facts.md §5.1).
  std::vector<std::uint8_t> extra;
};

/// The libusb calls the SDK makes. Every function returns 0 (or a count) on success and a
/// negative UsbError on failure, as libusb does. One object is one libusb context.
class UsbApi {
 public:
  virtual ~UsbApi() = default;

  virtual int init() = 0;    ///< libusb_init
  virtual void exit() = 0;   ///< libusb_exit (after every handle is closed)

  /// libusb_get_device_list: fills devices, returns their number or an error.
  virtual int get_device_list(std::vector<UsbDevice>& devices) = 0;
  /// libusb_free_device_list(list, 1): devices opened meanwhile stay valid through their handle.
  virtual void free_device_list() = 0;
  virtual int get_device_descriptor(UsbDevice device, UsbDeviceDescriptor& out) = 0;

  virtual int open(UsbDevice device, UsbHandle& out) = 0;  ///< libusb_open
  virtual void close(UsbHandle handle) = 0;               ///< libusb_close

  /// libusb_get_string_descriptor_ascii: the string at index into out.
  virtual int get_string_descriptor_ascii(UsbHandle handle, std::uint8_t index,
                                          std::string& out) = 0;

  virtual int kernel_driver_active(UsbHandle handle, int interface) = 0;  ///< 1 = yes, 0 = no
  virtual int detach_kernel_driver(UsbHandle handle, int interface) = 0;
  virtual int claim_interface(UsbHandle handle, int interface) = 0;
  virtual int release_interface(UsbHandle handle, int interface) = 0;

  /// libusb_bulk_transfer: OUT endpoints send length bytes from data (which is not modified), IN
  /// endpoints receive up to length bytes into it. transferred is set also on an error (a
  /// timeout may have moved some bytes). timeout_ms 0 means no timeout in libusb: the SDK never
  /// passes 0.
  virtual int bulk_transfer(UsbHandle handle, std::uint8_t endpoint, std::uint8_t* data,
                            int length, int& transferred, unsigned timeout_ms) = 0;

  // ---- used by the DfuSe client only. Not pure: a UsbApi that never serves DFU (a test's
  // backend) need not implement them, and then answers LIBUSB_ERROR_NOT_SUPPORTED.

  /// libusb_get_active_config_descriptor, flattened: every alternate setting of every interface
  /// of the device's active configuration, in the order of the descriptor.
  virtual int get_active_config_interfaces(UsbDevice /*device*/,
                                           std::vector<UsbAltSetting>& out) {
    out.clear();
    return kUsbErrorNotSupported;
  }
  /// libusb_set_interface_alt_setting (the interface must be claimed).
  virtual int set_interface_alt_setting(UsbHandle /*handle*/, int /*interface*/, int /*alt*/) {
    return kUsbErrorNotSupported;
  }
  /// libusb_control_transfer: a control transfer with this SETUP packet; an OUT request sends
  /// length bytes of data, an IN request receives up to length bytes into it. Returns the bytes
  /// moved or an error (kUsbErrorPipe: the device stalled the request). timeout_ms > 0.
  virtual int control_transfer(UsbHandle /*handle*/, std::uint8_t /*request_type*/,
                               std::uint8_t /*request*/, std::uint16_t /*value*/,
                               std::uint16_t /*index*/, std::uint8_t* /*data*/,
                               std::uint16_t /*length*/, unsigned /*timeout_ms*/) {
    return kUsbErrorNotSupported;
  }
};

/// The real UsbApi over libusb (libusb_api.cpp).
std::shared_ptr<UsbApi> make_libusb_api();

class HidApi;

// ---- shared by usb://, hid:// and discovery ------------------------------------------------

/// The identity to look for: the URI's vid/pid parameters, else DiscoveryOptions' (environment
/// PALP_USB_VID / PALP_USB_PID, else palp::proto::usb::kVendorId / kProductId).
struct UsbIdentity {
  std::uint16_t vid, pid;
};
UsbIdentity resolve_identity(const Uri& uri);

/// "vid 0x1209 pid 0x0001" for messages.
std::string describe_identity(UsbIdentity id);

/// What the serial-number choice found among the controllers of one identity.
struct SerialChoice {
  std::size_t index = 0;  ///< into the serials given, when ok
  bool ok = false;
  std::string error;      ///< the ConnectionError text when not ok
};

/// Picks the controller uri.serial names, or the only one when it is empty. serials: one entry
/// per controller found ("" when its serial could not be read). unreadable_why: why some could
/// not be read ("" when all were), with what to do about it. The error text names the URI, lists
/// the serials found, and says what to try.
SerialChoice choose_by_serial(const Uri& uri, UsbIdentity id,
                              const std::vector<std::string>& serials,
                              const std::string& unreadable_why);

/// The permissions hint appended to "access denied" errors.
inline constexpr const char* kPermissionHint =
    "install the udev rules (host/udev/70-palp.rules, e.g. into /etc/udev/rules.d, then "
    "`udevadm control --reload && udevadm trigger` and re-plug) or run as root";

/// The usb:// transport over the given UsbApi (tests pass a fake). Throws ConnectionError as
/// open_transport() does.
std::unique_ptr<Transport> open_usb_transport(const Uri& uri, std::chrono::milliseconds timeout,
                                              std::shared_ptr<UsbApi> api);

/// list_devices() over the given APIs (tests pass fakes); either may be null to skip it.
std::vector<DeviceListing> list_devices_with(const DiscoveryOptions& options, UsbApi* usb,
                                             HidApi* hid);

}  // namespace palp::detail
