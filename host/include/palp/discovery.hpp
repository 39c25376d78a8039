// SPDX-License-Identifier: Apache-2.0
// Discovery: every palp controller on this machine's USB, with its serial number, firmware
// version and the transports that reach it. None found is an empty list, never an error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace palp {

/// One controller. A controller that offers both the vendor interface and HID is one listing
/// with two URIs.
struct DeviceListing {
  std::string serial;            ///< USB iSerial ("" when the device could not be read)
  /// "major.minor" from bcdDevice (palp::proto::usb::bcd_device(): 0x0102 is "1.2"), or
  /// "unknown (bcdDevice 0x....)" when it is not BCD.
  std::string firmware_version;
  std::string product;           ///< USB iProduct ("" when the device could not be read)
  std::uint16_t vid = 0, pid = 0;
  /// The URIs that reach it, in this order: "usb://SERIAL" (the vendor interface, found by
  /// libusb), "hid://SERIAL" (the HID interface, found by hidapi). Empty when the serial could
  /// not be read (note says why).
  std::vector<std::string> uris;
  /// Why something is missing or will not work, with what to do: "cannot open over USB:
  /// LIBUSB_ERROR_ACCESS (permission denied: install the udev rules ...)". "" when all is well.
  std::string note;
};

struct DiscoveryOptions {
  std::uint16_t vid;  ///< default: PALP_USB_VID, else palp::proto::usb::kVendorId (0x1209)
  std::uint16_t pid;  ///< default: PALP_USB_PID, else palp::proto::usb::kProductId (0x0001)
  /// Reads PALP_USB_VID and PALP_USB_PID: hexadecimal as lsusb prints them ("1209", or
  /// "0x1209"); unset or empty means the default. Throws ConfigError naming the variable when
  /// one is not a USB ID. The usb:// and hid:// transports use the same defaults (a URI's
  /// ?vid=&pid= parameters override them).
  DiscoveryOptions();
};

/// Enumerates USB (libusb) and HID (hidapi) controllers with the given identity and merges the
/// two views by serial number. Returns an empty list when there are none, or when USB cannot be
/// enumerated at all on this machine (no /dev/bus/usb in a container, say).
std::vector<DeviceListing> list_devices(const DiscoveryOptions& options = {});

}  // namespace palp
