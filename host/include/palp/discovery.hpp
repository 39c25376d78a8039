// Discovery: every palp controller on this machine's USB, with its serial number, firmware
// version and the transports that reach it. None found is an empty list, never an error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace palp {

struct DeviceListing {
  std::string serial;            ///< USB iSerial ("" when the device could not be read)
  std::string firmware_version;  ///< "major.minor" from bcdDevice, or "major.minor.patch" once read
  std::string product;           ///< USB iProduct
  std::uint16_t vid = 0, pid = 0;
  std::vector<std::string> uris;  ///< the URIs that reach it: "usb://SERIAL", "hid://SERIAL"
  std::string note;               ///< why something is missing (permissions, interface claimed)
};

struct DiscoveryOptions {
  std::uint16_t vid;  ///< default: palp::proto::usb::kVendorId or PALP_USB_VID
  std::uint16_t pid;  ///< default: palp::proto::usb::kProductId or PALP_USB_PID
  DiscoveryOptions();
};

/// Enumerates USB (libusb) and HID (hidapi) controllers with the given identity and merges the
/// two views by serial number. Returns an empty list when there are none, or when USB cannot be
/// enumerated at all on this machine (no /dev/bus/usb in a container, say).
std::vector<DeviceListing> list_devices(const DiscoveryOptions& options = {});

}  // namespace palp
