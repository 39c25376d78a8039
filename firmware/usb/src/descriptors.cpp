// SPDX-License-Identifier: Apache-2.0
// The descriptors (descriptors.hpp), built at compile time by a small byte writer whose size is
// computed from the layout and checked against what was written. Field layouts and values cite
// ../shared/reference/usb-dfu-facts.md ("facts §n"); every multi-byte field is little-endian.
#include "palp/usb/descriptors.hpp"

#include <array>
#include <cstddef>

#include "palp/fw/controller.hpp"
#include "palp/protocol/usb.hpp"
#include "palp/usb/hid_report.hpp"

namespace palp::usb {
namespace {

namespace pu = palp::proto::usb;

/// A descriptor under construction: N bytes, written front to back. Writing past N is not a
/// constant expression, so an overrun fails the build; the static_asserts below check that all N
/// were written.
template <std::size_t N>
struct Writer {
  std::array<std::uint8_t, N> bytes{};
  std::size_t size = 0;

  constexpr Writer& u8(unsigned v) {
    bytes[size++] = static_cast<std::uint8_t>(v);
    return *this;
  }
  constexpr Writer& u16(unsigned v) { return u8(v & 0xFFu).u8((v >> 8) & 0xFFu); }
  constexpr Writer& u32(std::uint32_t v) { return u16(v & 0xFFFFu).u16(v >> 16); }
  /// ASCII text as UTF-16LE code units (no terminator).
  constexpr Writer& utf16(const char* ascii) {
    for (; *ascii != '\0'; ++ascii) u16(static_cast<unsigned char>(*ascii));
    return *this;
  }
  constexpr Writer& raw(const std::uint8_t* from, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) u8(from[k]);
    return *this;
  }
};

constexpr std::size_t length_of(const char* ascii) {
  std::size_t n = 0;
  while (ascii[n] != '\0') ++n;
  return n;
}

// ---- descriptor type codes (facts §1.3) and sizes (facts §1.4-§1.7, §2.1, §3, §4) --------------
constexpr std::uint8_t kTypeDevice = 0x01, kTypeConfiguration = 0x02, kTypeString = 0x03,
                       kTypeInterface = 0x04, kTypeEndpoint = 0x05, kTypeBos = 0x0F,
                       kTypeDeviceCapability = 0x10, kTypeHid = 0x21, kTypeHidReport = 0x22;
constexpr std::size_t kDeviceSize = 18, kConfigurationSize = 9, kInterfaceSize = 9,
                      kEndpointSize = 7, kHidSize = 9, kBosHeaderSize = 5, kPlatformCapSize = 28;

constexpr std::uint16_t kLangIdEnUs = 0x0409;  // facts §1.8
constexpr std::uint8_t kEndpointBulk = 0x02, kEndpointInterrupt = 0x03;  // facts §1.7
constexpr std::uint8_t kInterfaceClassHid = 0x03;                        // facts §1.6

// ---- device descriptor (facts §1.4) -------------------------------------------------------------
// bcdUSB 0x0201: Windows asks for the BOS only when bcdUSB >= 0x0201 (facts §3, MSBLOG); 2.01
// claims nothing of USB 2.1 beyond the BOS (no LPM, so no USB 2.0 extension capability).
constexpr std::uint16_t kBcdUsb = 0x0201;
constexpr fw::DeviceIdentity kCoreIdentity{};  // the version the core reports in DeviceInfo
constexpr std::uint16_t kBcdDevice = pu::bcd_device(kCoreIdentity.fw_major, kCoreIdentity.fw_minor);
constexpr std::uint8_t kMaxPacketSize0 = 64;

constexpr auto kDevice = [] {
  Writer<kDeviceSize> w;
  w.u8(kDeviceSize).u8(kTypeDevice).u16(kBcdUsb);
  w.u8(0x00).u8(0x00).u8(0x00);  // class per interface, no IAD (facts §1.9, §4.5)
  w.u8(kMaxPacketSize0).u16(pu::kVendorId).u16(pu::kProductId).u16(kBcdDevice);
  w.u8(kStringManufacturer).u8(kStringProduct).u8(kStringSerialNumber);
  w.u8(1);  // bNumConfigurations
  return w;
}();
static_assert(kDevice.size == kDeviceSize);

// ---- configuration block (facts §1.5-§1.7, §2.1) ------------------------------------------------
constexpr std::uint8_t kConfigurationValue = 1;
constexpr std::uint8_t kAttributesBusPowered = 0x80;  // D7 must be 1; not self-powered, no wakeup
constexpr std::uint8_t kMaxPower2mA = 50;             // 100 mA, one unit load
constexpr std::uint8_t kBulkInterval = 0;             // ignored for full-speed bulk
constexpr std::size_t kConfigurationTotal = kConfigurationSize +
                                            kInterfaceSize + 2 * kEndpointSize +             // 0
                                            kInterfaceSize + kHidSize + 2 * kEndpointSize;   // 1
static_assert(kConfigurationTotal == 64, "9 + 23 + 32: an exact EP0 packet (the core sends a ZLP)");

template <std::size_t N>
constexpr void interface(Writer<N>& w, std::uint8_t number, std::uint8_t klass, std::uint8_t name) {
  w.u8(kInterfaceSize).u8(kTypeInterface).u8(number).u8(0 /* alternate */).u8(2 /* endpoints */);
  w.u8(klass).u8(0 /* subclass: none (HID: not boot) */).u8(0 /* protocol */).u8(name);
}
template <std::size_t N>
constexpr void endpoint(Writer<N>& w, std::uint8_t address, std::uint8_t type,
                        std::uint16_t max_packet, std::uint8_t interval) {
  w.u8(kEndpointSize).u8(kTypeEndpoint).u8(address).u8(type).u16(max_packet).u8(interval);
}

constexpr auto kConfiguration = [] {
  Writer<kConfigurationTotal> w;
  w.u8(kConfigurationSize).u8(kTypeConfiguration).u16(kConfigurationTotal);
  w.u8(2 /* interfaces */).u8(kConfigurationValue).u8(0 /* no name */);
  w.u8(kAttributesBusPowered).u8(kMaxPower2mA);

  interface(w, pu::kVendorInterface, pu::kVendorInterfaceClass, kStringVendorInterface);
  endpoint(w, pu::kBulkOutEndpoint, kEndpointBulk, pu::kBulkPacketSize, kBulkInterval);
  endpoint(w, pu::kBulkInEndpoint, kEndpointBulk, pu::kBulkPacketSize, kBulkInterval);

  interface(w, pu::kHidInterface, kInterfaceClassHid, kStringHidInterface);
  w.u8(kHidSize).u8(kTypeHid).u16(0x0111 /* bcdHID 1.11 */).u8(0 /* not localised */);
  w.u8(1 /* class descriptors */).u8(kTypeHidReport).u16(kHidReport.size());
  endpoint(w, pu::kHidOutEndpoint, kEndpointInterrupt, pu::kHidReportSize, pu::kHidIntervalMs);
  endpoint(w, pu::kHidInEndpoint, kEndpointInterrupt, pu::kHidReportSize, pu::kHidIntervalMs);
  return w;
}();
static_assert(kConfiguration.size == kConfigurationTotal);
/// Where the HID descriptor sits in the block (served alone for GET_DESCRIPTOR(0x21)).
constexpr std::size_t kHidOffset = kConfigurationSize + kInterfaceSize + 2 * kEndpointSize +
                                   kInterfaceSize;
static_assert(kConfiguration.bytes[kHidOffset + 1] == kTypeHid);

// ---- strings (facts §1.8) -----------------------------------------------------------------------
constexpr std::array<std::uint8_t, 4> kLangIds{4, kTypeString, kLangIdEnUs & 0xFF, kLangIdEnUs >> 8};

template <std::size_t Chars>
constexpr auto string_descriptor(const char* ascii) {
  Writer<2 + 2 * Chars> w;
  w.u8(2 + 2 * Chars).u8(kTypeString).utf16(ascii);
  return w;
}
#define PALP_USB_STRING(text) string_descriptor<length_of(text)>(text)
constexpr auto kManufacturer = PALP_USB_STRING("palp");
constexpr auto kProduct = PALP_USB_STRING("palp probe controller");
constexpr auto kVendorInterfaceName = PALP_USB_STRING("palp byte stream (bulk)");
constexpr auto kHidInterfaceName = PALP_USB_STRING("palp byte stream (HID)");
#undef PALP_USB_STRING

/// The serial number: set at boot (set_serial_number), "0" until then.
struct Serial {
  std::array<std::uint8_t, 2 + 2 * kMaxSerialChars> bytes{4, kTypeString, '0', 0};
  std::size_t size = 4;
};
constinit Serial g_serial;

// ---- BOS with the MS OS 2.0 platform capability (facts §3, §4.1) ---------------------------------
constexpr std::uint8_t kCapabilityPlatform = 0x05;
/// {D8DD60DF-4589-4CC7-9CD2-659D9E648A9F} in Microsoft's byte order (facts §4.1).
constexpr std::array<std::uint8_t, 16> kMsOs20PlatformUuid{0xDF, 0x60, 0xDD, 0xD8, 0x89, 0x45,
                                                           0xC7, 0x4C, 0x9C, 0xD2, 0x65, 0x9D,
                                                           0x9E, 0x64, 0x8A, 0x9F};
constexpr std::uint32_t kWindows81 = 0x06030000;  // NTDDI_WINBLUE (facts §4.1)

// ---- MS OS 2.0 descriptor set, composite form (facts §4.2, §4.3, §4.5) ---------------------------
constexpr std::uint16_t kMsSetHeader = 0x00, kMsConfigurationSubset = 0x01,
                        kMsFunctionSubset = 0x02, kMsCompatibleId = 0x03,
                        kMsRegistryProperty = 0x04;
constexpr std::uint16_t kRegMultiSz = 7;
constexpr const char* kGuidPropertyName = "DeviceInterfaceGUIDs";
constexpr std::size_t kSetHeaderSize = 10, kSubsetHeaderSize = 8, kCompatibleIdSize = 20;
constexpr std::size_t kPropertyNameBytes = 2 * (length_of(kGuidPropertyName) + 1);  // + NUL
// REG_MULTI_SZ: the GUID, its NUL and the list's closing NUL (facts §4.3: two NULs)
constexpr std::size_t kPropertyDataBytes = 2 * (length_of(kDeviceInterfaceGuid) + 2);
constexpr std::size_t kRegistryPropertySize = 10 + kPropertyNameBytes + kPropertyDataBytes;
constexpr std::size_t kFunctionSubsetTotal =
    kSubsetHeaderSize + kCompatibleIdSize + kRegistryPropertySize;
constexpr std::size_t kConfigurationSubsetTotal = kSubsetHeaderSize + kFunctionSubsetTotal;
constexpr std::size_t kMsOs20SetTotal = kSetHeaderSize + kConfigurationSubsetTotal;
static_assert(length_of(kDeviceInterfaceGuid) == 38);
static_assert(kRegistryPropertySize == 132 && kMsOs20SetTotal == 178);  // facts §4.3's sizes

constexpr auto kMsOs20Set = [] {
  Writer<kMsOs20SetTotal> w;
  w.u16(kSetHeaderSize).u16(kMsSetHeader).u32(kWindows81).u16(kMsOs20SetTotal);
  // bConfigurationValue: Windows matches the configuration's index here (0 = the first), as
  // TinyUSB's working examples write it, not the value SET_CONFIGURATION uses (facts §4.3)
  w.u16(kSubsetHeaderSize).u16(kMsConfigurationSubset).u8(0).u8(0).u16(kConfigurationSubsetTotal);
  // the vendor interface only: the HID interface keeps the in-box HID driver (facts §4.5)
  w.u16(kSubsetHeaderSize).u16(kMsFunctionSubset).u8(pu::kVendorInterface).u8(0);
  w.u16(kFunctionSubsetTotal);
  w.u16(kCompatibleIdSize).u16(kMsCompatibleId);
  for (char c : {'W', 'I', 'N', 'U', 'S', 'B', '\0', '\0'}) w.u8(static_cast<unsigned char>(c));
  for (int k = 0; k < 8; ++k) w.u8(0);  // SubCompatibleID
  w.u16(kRegistryPropertySize).u16(kMsRegistryProperty).u16(kRegMultiSz);
  w.u16(kPropertyNameBytes).utf16(kGuidPropertyName).u16(0);
  w.u16(kPropertyDataBytes).utf16(kDeviceInterfaceGuid).u16(0).u16(0);
  return w;
}();
static_assert(kMsOs20Set.size == kMsOs20SetTotal);

constexpr std::size_t kBosTotal = kBosHeaderSize + kPlatformCapSize;
static_assert(kBosTotal == 33);  // facts §4.1
constexpr auto kBos = [] {
  Writer<kBosTotal> w;
  w.u8(kBosHeaderSize).u8(kTypeBos).u16(kBosTotal).u8(1 /* capabilities */);
  w.u8(kPlatformCapSize).u8(kTypeDeviceCapability).u8(kCapabilityPlatform).u8(0 /* reserved */);
  w.raw(kMsOs20PlatformUuid.data(), kMsOs20PlatformUuid.size());
  w.u32(kWindows81).u16(kMsOs20SetTotal).u8(kMsOs20VendorCode).u8(0 /* no alternate enum */);
  return w;
}();
static_assert(kBos.size == kBosTotal);

template <std::size_t N>
constexpr std::span<const std::uint8_t> span_of(const Writer<N>& w) {
  return {w.bytes.data(), w.size};
}

std::span<const std::uint8_t> find_string(std::uint8_t index, std::uint16_t langid) {
  if (index == 0) return kLangIds;
  if (langid != kLangIdEnUs && langid != 0) return {};
  switch (index) {
    case kStringManufacturer: return span_of(kManufacturer);
    case kStringProduct: return span_of(kProduct);
    case kStringSerialNumber: return {g_serial.bytes.data(), g_serial.size};
    case kStringVendorInterface: return span_of(kVendorInterfaceName);
    case kStringHidInterface: return span_of(kHidInterfaceName);
    default: return {};
  }
}

}  // namespace

std::span<const std::uint8_t> find_descriptor(std::uint8_t type, std::uint8_t index,
                                              std::uint16_t langid) {
  if (type == kTypeString) return find_string(index, langid);
  if (index != 0) return {};
  switch (type) {
    case kTypeDevice: return span_of(kDevice);
    case kTypeConfiguration: return span_of(kConfiguration);
    case kTypeBos: return span_of(kBos);
    case kTypeHid:
      if (langid != pu::kHidInterface) return {};
      return span_of(kConfiguration).subspan(kHidOffset, kHidSize);
    case kTypeHidReport:
      if (langid != pu::kHidInterface) return {};
      return kHidReport;
    default: return {};
  }
}

std::span<const std::uint8_t> ms_os_20_descriptor_set() { return span_of(kMsOs20Set); }

bool set_serial_number(const char* ascii) {
  bool clean = ascii != nullptr && ascii[0] != '\0';
  std::size_t n = 0;
  if (clean) {
    for (; ascii[n] != '\0'; ++n) {
      if (n == kMaxSerialChars) {
        clean = false;
        break;
      }
      const auto c = static_cast<unsigned char>(ascii[n]);
      const bool printable = c >= 0x20 && c <= 0x7E;
      clean = clean && printable;
      g_serial.bytes[2 + 2 * n] = printable ? c : static_cast<std::uint8_t>('?');
      g_serial.bytes[3 + 2 * n] = 0;
    }
  } else {
    g_serial.bytes[2] = '0';
    g_serial.bytes[3] = 0;
    n = 1;
  }
  g_serial.size = 2 + 2 * n;
  g_serial.bytes[0] = static_cast<std::uint8_t>(g_serial.size);
  return clean;
}

}  // namespace palp::usb
