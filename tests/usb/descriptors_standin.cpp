// STAND-IN descriptors for the device core's tests, linked only while palp_usb_device has no
// descriptors source of its own (tests/usb/CMakeLists.txt): helper usbdesc's descriptors.cpp
// replaces it at the merge. The tests never look inside these bytes (they compare what the
// device sends with find_descriptor's answer); only the lengths matter, and they are those of
// usbdesc's descriptors: device 18, configuration 64, BOS 33, HID report 34, MS OS 2.0 set 178.
#include <array>
#include <cstring>

#include "palp/usb/descriptors.hpp"

namespace palp::usb {
namespace {

template <std::size_t N>
constexpr std::array<std::uint8_t, N> filled(std::uint8_t length, std::uint8_t type,
                                             std::uint8_t seed) {
  std::array<std::uint8_t, N> d{};
  for (std::size_t k = 0; k < N; ++k) d[k] = static_cast<std::uint8_t>(seed + 7 * k);
  d[0] = length;
  d[1] = type;
  return d;
}

constexpr std::array<std::uint8_t, 18> kDevice = {18,   0x01, 0x01, 0x02, 0, 0, 0, 64,
                                                  0x09, 0x12, 0x01, 0x00, 0, 1, 1, 2, 3, 1};
// 64 bytes: bus-powered (bmAttributes 0x80), wTotalLength 64
constexpr auto kConfiguration = [] {
  auto d = filled<64>(9, 0x02, 0x30);
  d[2] = 64;
  d[3] = 0;
  d[7] = 0x80;
  return d;
}();
constexpr auto kBos = filled<33>(5, 0x0F, 0x50);
constexpr auto kHid = filled<9>(9, 0x21, 0x60);
constexpr auto kHidReport = filled<34>(0x06, 0x00, 0x70);
constexpr auto kMsOs20Set = filled<178>(10, 0x00, 0x11);
constexpr std::array<std::uint8_t, 4> kLangIds = {4, 0x03, 0x09, 0x04};
constexpr std::array<std::uint8_t, 12> kProduct = {12, 0x03, 'p', 0, 'a', 0, 'l', 0, 'p', 0, '!', 0};
std::array<std::uint8_t, 2 + 2 * 24> serial = {4, 0x03, '0', 0};

}  // namespace

std::span<const std::uint8_t> find_descriptor(std::uint8_t type, std::uint8_t index,
                                              std::uint16_t langid) {
  switch (type) {
    case 0x01: return index == 0 ? std::span<const std::uint8_t>(kDevice) : std::span<const std::uint8_t>{};
    case 0x02: return index == 0 ? std::span<const std::uint8_t>(kConfiguration) : std::span<const std::uint8_t>{};
    case 0x03:
      if (index == 0) return kLangIds;
      if (langid != 0x0409 && langid != 0) return {};
      if (index == 2) return kProduct;
      if (index == 3) return std::span<const std::uint8_t>(serial.data(), serial[0]);
      return {};
    case 0x0F: return index == 0 ? std::span<const std::uint8_t>(kBos) : std::span<const std::uint8_t>{};
    case 0x21: return langid == 1 ? std::span<const std::uint8_t>(kHid) : std::span<const std::uint8_t>{};
    case 0x22: return langid == 1 ? std::span<const std::uint8_t>(kHidReport) : std::span<const std::uint8_t>{};
    default: return {};
  }
}

std::span<const std::uint8_t> ms_os_20_descriptor_set() { return kMsOs20Set; }

bool set_serial_number(const char* ascii) {
  const std::size_t n = std::min<std::size_t>(std::strlen(ascii), 24);
  serial[0] = static_cast<std::uint8_t>(2 + 2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    serial[2 + 2 * k] = static_cast<std::uint8_t>(ascii[k]);
    serial[3 + 2 * k] = 0;
  }
  return true;
}

}  // namespace palp::usb
