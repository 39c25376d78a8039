// SPDX-License-Identifier: Apache-2.0
// The real HidApi (hid_api.hpp): each call is the hidapi call of the same name; strings are
// converted between hidapi's wchar_t and UTF-8.
//
// hid_exit() is never called: hidapi's state is process-wide, and another transport or a
// discovery may be using it; the operating system frees it at exit.
#include <hidapi.h>

#include <cwchar>

#include "transport/hid_api.hpp"

namespace palp::detail {
namespace {

hid_device* dev(HidHandle h) {
  return reinterpret_cast<hid_device*>(static_cast<std::uintptr_t>(h));
}

void put_utf8(std::string& out, std::uint32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x110000) {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += '?';
  }
}

std::string to_utf8(const wchar_t* w) {
  std::string out;
  if (w == nullptr) return out;
  for (; *w != L'\0'; ++w) put_utf8(out, static_cast<std::uint32_t>(*w));
  return out;
}

std::wstring from_utf8(const std::string& s) {
  std::wstring out;
  for (std::size_t k = 0; k < s.size();) {
    const auto b = static_cast<unsigned char>(s[k]);
    const int extra = b < 0x80 ? 0 : b < 0xE0 ? 1 : b < 0xF0 ? 2 : 3;
    std::uint32_t c = extra == 0 ? b : extra == 1 ? (b & 0x1Fu) : extra == 2 ? (b & 0x0Fu)
                                                                             : (b & 0x07u);
    ++k;
    for (int e = 0; e < extra && k < s.size(); ++e, ++k)
      c = (c << 6) | (static_cast<unsigned char>(s[k]) & 0x3Fu);
    out += static_cast<wchar_t>(c);
  }
  return out;
}

class Hidapi final : public HidApi {
 public:
  Hidapi() { hid_init(); }

  std::vector<HidDeviceInfo> enumerate(std::uint16_t vid, std::uint16_t pid) override {
    std::vector<HidDeviceInfo> out;
    hid_device_info* list = hid_enumerate(vid, pid);
    for (const hid_device_info* d = list; d != nullptr; d = d->next) {
      HidDeviceInfo i;
      i.path = d->path != nullptr ? d->path : "";
      i.vid = d->vendor_id;
      i.pid = d->product_id;
      i.serial = to_utf8(d->serial_number);
      i.release_number = d->release_number;
      i.product = to_utf8(d->product_string);
      i.interface_number = d->interface_number;
      out.push_back(std::move(i));
    }
    hid_free_enumeration(list);
    return out;
  }

  bool open(std::uint16_t vid, std::uint16_t pid, const std::string& serial,
            HidHandle& out) override {
    const std::wstring w = from_utf8(serial);
    hid_device* d = hid_open(vid, pid, serial.empty() ? nullptr : w.c_str());
    if (d == nullptr) return false;
    out = static_cast<HidHandle>(reinterpret_cast<std::uintptr_t>(d));
    return true;
  }

  void close(HidHandle handle) override { hid_close(dev(handle)); }

  int write(HidHandle handle, const std::uint8_t* data, std::size_t length) override {
    return hid_write(dev(handle), data, length);
  }

  int read_timeout(HidHandle handle, std::uint8_t* data, std::size_t length,
                   int timeout_ms) override {
    return hid_read_timeout(dev(handle), data, length, timeout_ms);
  }

  std::string error(const HidHandle* handle) override {
    const wchar_t* e = hid_error(handle != nullptr ? dev(*handle) : nullptr);
    return e != nullptr ? to_utf8(e) : "unknown error";
  }
};

}  // namespace

std::shared_ptr<HidApi> make_hidapi_api() { return std::make_shared<Hidapi>(); }

}  // namespace palp::detail
