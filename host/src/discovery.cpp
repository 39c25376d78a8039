// SPDX-License-Identifier: Apache-2.0
// Discovery (discovery.hpp): the USB view (libusb: every device with the identity, opened to
// read its serial number and product string, then closed) and the HID view (hidapi's
// enumeration, and a trial open for the permissions note), merged by serial number.
//
// A USB device whose serial could not be read (no permission to open it) is merged with the one
// HID controller of the same bcdDevice that no USB device claimed by serial, when there is
// exactly one of each (hidapi reads the serial without opening the device); otherwise it is
// listed on its own, without URIs, and its note says why.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "palp/discovery.hpp"
#include "palp/error.hpp"
#include "palp/protocol/usb.hpp"
#include "transport/hid_api.hpp"
#include "transport/usb_api.hpp"

namespace palp {
namespace {

namespace pu = palp::proto::usb;

/// An environment override of a USB ID: hexadecimal as lsusb prints it ("1209"), with or without
/// "0x". Unset or empty: the default.
std::uint16_t env_id(const char* name, std::uint16_t fallback) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return fallback;
  std::string_view v(text);
  if (v.size() > 2 && v[0] == '0' && (v[1] == 'x' || v[1] == 'X')) v.remove_prefix(2);
  unsigned value = 0;
  bool ok = !v.empty() && v.size() <= 4;
  for (const char c : v) {
    const int d = c >= '0' && c <= '9'   ? c - '0'
                  : c >= 'a' && c <= 'f' ? c - 'a' + 10
                  : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                         : -1;
    if (d < 0) ok = false;
    else value = value * 16 + static_cast<unsigned>(d);
  }
  if (!ok)
    throw ConfigError(std::string(name) + "='" + text +
                      "' is not a USB ID (up to 4 hex digits, e.g. 1209 or 0x1209)");
  return static_cast<std::uint16_t>(value);
}

std::string firmware_version(std::uint16_t bcd) {
  char buf[40];
  if (pu::bcd_device_valid(bcd))
    std::snprintf(buf, sizeof buf, "%u.%u", pu::bcd_device_major(bcd), pu::bcd_device_minor(bcd));
  else
    std::snprintf(buf, sizeof buf, "unknown (bcdDevice 0x%04x)", bcd);
  return buf;
}

void add_note(DeviceListing& l, const std::string& note) {
  l.note += (l.note.empty() ? "" : "; ") + note;
}

struct Entry {
  DeviceListing listing;
  std::uint16_t bcd = 0;
  bool hid = false;  ///< the HID view found it
};

void usb_view(const DiscoveryOptions& o, detail::UsbApi& usb, std::vector<Entry>& out) {
  if (usb.init() < 0) return;  // no USB here (a container without /dev/bus/usb, say)
  std::vector<detail::UsbDevice> devices;
  if (usb.get_device_list(devices) >= 0) {
    for (const detail::UsbDevice d : devices) {
      detail::UsbDeviceDescriptor desc;
      if (usb.get_device_descriptor(d, desc) < 0 || desc.vid != o.vid || desc.pid != o.pid)
        continue;
      Entry e;
      e.bcd = desc.bcd_device;
      e.listing.vid = desc.vid;
      e.listing.pid = desc.pid;
      e.listing.firmware_version = firmware_version(desc.bcd_device);
      detail::UsbHandle h{};
      if (const int r = usb.open(d, h); r < 0) {
        add_note(e.listing, "cannot open over USB: " + detail::usb_error_name(r) +
                                (r == detail::kUsbErrorAccess
                                     ? std::string(" (permission denied: ") +
                                           detail::kPermissionHint + ")"
                                     : std::string()));
      } else {
        if (desc.i_serial != 0 &&
            usb.get_string_descriptor_ascii(h, desc.i_serial, e.listing.serial) < 0)
          e.listing.serial.clear();
        if (desc.i_product != 0 &&
            usb.get_string_descriptor_ascii(h, desc.i_product, e.listing.product) < 0)
          e.listing.product.clear();
        usb.close(h);
        if (e.listing.serial.empty()) add_note(e.listing, "the serial number could not be read");
      }
      out.push_back(std::move(e));
    }
    usb.free_device_list();
  }
  usb.exit();
}

void hid_view(const DiscoveryOptions& o, detail::HidApi& hid, std::vector<Entry>& out) {
  const std::size_t usb_count = out.size();
  std::vector<detail::HidDeviceInfo> unmatched;
  for (const detail::HidDeviceInfo& i : hid.enumerate(o.vid, o.pid)) {
    if (i.vid != o.vid || i.pid != o.pid) continue;
    Entry* match = nullptr;
    for (std::size_t k = 0; k < usb_count && !i.serial.empty(); ++k)
      if (!out[k].hid && out[k].listing.serial == i.serial) match = &out[k];
    if (match == nullptr) {
      unmatched.push_back(i);
      continue;
    }
    match->hid = true;
    if (match->listing.product.empty()) match->listing.product = i.product;
  }
  std::vector<Entry*> unknown_usb;
  for (std::size_t k = 0; k < usb_count; ++k)
    if (out[k].listing.serial.empty()) unknown_usb.push_back(&out[k]);
  for (const detail::HidDeviceInfo& i : unmatched) {
    if (unknown_usb.size() == 1 && unmatched.size() == 1 && !i.serial.empty() &&
        unknown_usb[0]->bcd == i.release_number) {
      Entry& e = *unknown_usb[0];
      e.hid = true;
      e.listing.serial = i.serial;
      if (e.listing.product.empty()) e.listing.product = i.product;
      continue;
    }
    Entry e;
    e.hid = true;
    e.bcd = i.release_number;
    e.listing.serial = i.serial;
    e.listing.product = i.product;
    e.listing.vid = i.vid;
    e.listing.pid = i.pid;
    e.listing.firmware_version = firmware_version(i.release_number);
    out.push_back(std::move(e));
  }
  // A trial open of each HID controller: a permissions problem is said here, not at connect.
  for (Entry& e : out) {
    if (!e.hid) continue;
    detail::HidHandle h{};
    if (hid.open(o.vid, o.pid, e.listing.serial, h)) {
      hid.close(h);
      continue;
    }
    const std::string why = hid.error(nullptr);
    add_note(e.listing, "cannot open over HID: " + why +
                            (why.find("Permission denied") != std::string::npos
                                 ? std::string(" (") + detail::kPermissionHint + ")"
                                 : std::string()));
  }
}

}  // namespace

DiscoveryOptions::DiscoveryOptions()
    : vid(env_id("PALP_USB_VID", pu::kVendorId)), pid(env_id("PALP_USB_PID", pu::kProductId)) {}

namespace detail {

std::vector<DeviceListing> list_devices_with(const DiscoveryOptions& options, UsbApi* usb,
                                             HidApi* hid) {
  std::vector<Entry> entries;
  if (usb != nullptr) usb_view(options, *usb, entries);
  const std::size_t usb_count = entries.size();
  if (hid != nullptr) hid_view(options, *hid, entries);
  std::vector<DeviceListing> out;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    DeviceListing& l = entries[k].listing;
    const bool on_usb = k < usb_count;
    if (!l.serial.empty()) {  // a controller without a readable serial cannot be named
      if (on_usb) l.uris.push_back("usb://" + l.serial);
      if (entries[k].hid) l.uris.push_back("hid://" + l.serial);
    }
    out.push_back(std::move(l));
  }
  std::sort(out.begin(), out.end(), [](const DeviceListing& a, const DeviceListing& b) {
    return a.serial < b.serial;
  });
  return out;
}

}  // namespace detail

std::vector<DeviceListing> list_devices(const DiscoveryOptions& options) {
  const std::shared_ptr<detail::UsbApi> usb = detail::make_libusb_api();
  const std::shared_ptr<detail::HidApi> hid = detail::make_hidapi_api();
  return detail::list_devices_with(options, usb.get(), hid.get());
}

}  // namespace palp
