// SPDX-License-Identifier: Apache-2.0
// The independent descriptor decoder (usb_decoder.hpp). Offsets and codes from
// ../shared/reference/usb-dfu-facts.md, section named at each; all fields little-endian (sheet
// preamble).
#include "usb_decoder.hpp"

#include <set>

namespace palp::test::usbdec {
namespace {

[[noreturn]] void fail(const std::string& what) { throw DecodeError(what); }

/// Reads little-endian fields from b, checking every read is inside it.
class Cursor {
 public:
  Cursor(Bytes b, std::string what) : b_(b), what_(std::move(what)) {}
  std::size_t at() const { return at_; }
  std::size_t size() const { return b_.size(); }
  void seek(std::size_t at) { at_ = at; }
  void need(std::size_t n) const {
    if (at_ + n > b_.size())
      fail(what_ + ": " + std::to_string(n) + " bytes needed at offset " + std::to_string(at_) +
           ", only " + std::to_string(b_.size() - at_) + " left");
  }
  std::uint8_t u8() {
    need(1);
    return b_[at_++];
  }
  std::uint16_t u16() {
    const std::uint16_t lo = u8();
    return static_cast<std::uint16_t>(lo | (u8() << 8));
  }
  std::uint32_t u32() {
    const std::uint32_t lo = u16();
    return lo | (static_cast<std::uint32_t>(u16()) << 16);
  }
  std::uint8_t peek(std::size_t ahead) const {
    if (at_ + ahead >= b_.size()) fail(what_ + ": truncated at offset " + std::to_string(at_));
    return b_[at_ + ahead];
  }

 private:
  Bytes b_;
  std::string what_;
  std::size_t at_ = 0;
};

void expect(bool ok, const std::string& what) {
  if (!ok) fail(what);
}
std::string hex(unsigned v) {
  static const char* digits = "0123456789ABCDEF";
  std::string s;
  do {
    s.insert(s.begin(), digits[v & 0xF]);
    v >>= 4;
  } while (v != 0);
  return "0x" + s;
}

// facts §1.3
constexpr std::uint8_t kDevice = 0x01, kConfiguration = 0x02, kString = 0x03, kInterface = 0x04,
                       kEndpoint = 0x05, kBos = 0x0F, kCapability = 0x10, kHid = 0x21;

}  // namespace

Device decode_device(Bytes b) {
  // facts §1.4: 18 bytes
  expect(b.size() == 18, "device descriptor: " + std::to_string(b.size()) + " bytes, not 18");
  Cursor c(b, "device descriptor");
  expect(c.u8() == 18, "device descriptor: bLength is not 18");
  expect(c.u8() == kDevice, "device descriptor: bDescriptorType is not 0x01");
  Device d;
  d.bcd_usb = c.u16();
  d.device_class = c.u8();
  d.device_subclass = c.u8();
  d.device_protocol = c.u8();
  d.max_packet0 = c.u8();
  expect(d.max_packet0 == 8 || d.max_packet0 == 16 || d.max_packet0 == 32 || d.max_packet0 == 64,
         "device descriptor: bMaxPacketSize0 " + std::to_string(d.max_packet0) +
             " is not 8, 16, 32 or 64");
  d.vendor = c.u16();
  d.product = c.u16();
  d.bcd_device = c.u16();
  d.i_manufacturer = c.u8();
  d.i_product = c.u8();
  d.i_serial = c.u8();
  d.num_configurations = c.u8();
  return d;
}

Configuration decode_configuration(Bytes b) {
  // facts §1.5: 9-byte header, then interfaces (§1.6, 9), HID (§2.1, 6 + 3 per class
  // descriptor), endpoints (§1.7, 7)
  Cursor c(b, "configuration block");
  expect(c.u8() == 9, "configuration descriptor: bLength is not 9");
  expect(c.u8() == kConfiguration, "configuration descriptor: bDescriptorType is not 0x02");
  Configuration cfg;
  cfg.total_length = c.u16();
  expect(cfg.total_length == b.size(), "configuration: wTotalLength " +
                                           std::to_string(cfg.total_length) + " but the block has " +
                                           std::to_string(b.size()) + " bytes");
  cfg.num_interfaces = c.u8();
  cfg.value = c.u8();
  cfg.i_configuration = c.u8();
  cfg.attributes = c.u8();
  cfg.max_power = c.u8();
  expect((cfg.attributes & 0x80) != 0, "configuration: bmAttributes D7 (must be 1) is 0");
  expect((cfg.attributes & 0x1F) == 0, "configuration: bmAttributes reserved bits 4..0 set");

  std::vector<std::uint8_t> declared_endpoints;  // bNumEndpoints of each interface
  while (c.at() < c.size()) {
    const std::size_t start = c.at();
    const std::uint8_t length = c.peek(0), type = c.peek(1);
    const std::string where = " at offset " + std::to_string(start);
    expect(length >= 2 && start + length <= b.size(),
           "descriptor" + where + ": bLength " + std::to_string(length) + " runs past the block");
    c.u8();
    c.u8();
    if (type == kInterface) {
      expect(length == 9, "interface descriptor" + where + ": bLength is not 9");
      Interface i;
      i.number = c.u8();
      i.alternate = c.u8();
      declared_endpoints.push_back(c.u8());
      i.interface_class = c.u8();
      i.subclass = c.u8();
      i.protocol = c.u8();
      i.i_interface = c.u8();
      cfg.interfaces.push_back(i);
    } else if (type == kHid) {
      expect(!cfg.interfaces.empty() && cfg.interfaces.back().interface_class == 0x03,
             "HID descriptor" + where + " not after a HID interface (class 0x03)");
      Interface& i = cfg.interfaces.back();
      expect(!i.hid && i.endpoints.empty(),
             "HID descriptor" + where + " not right after its interface descriptor");
      HidClassDescriptor h;
      h.bcd_hid = c.u16();
      h.country = c.u8();
      const std::uint8_t n = c.u8();
      expect(n >= 1 && length == 6 + 3 * n,
             "HID descriptor" + where + ": bLength " + std::to_string(length) + " for " +
                 std::to_string(n) + " class descriptors (6 + 3 each)");
      h.report_type = c.u8();
      h.report_length = c.u16();
      c.seek(start + length);
      i.hid = h;
    } else if (type == kEndpoint) {
      expect(length == 7, "endpoint descriptor" + where + ": bLength is not 7");
      expect(!cfg.interfaces.empty(), "endpoint descriptor" + where + " before any interface");
      Endpoint e;
      e.address = c.u8();
      const std::uint8_t attributes = c.u8();
      e.transfer_type = attributes & 0x03;
      const std::uint16_t w_max = c.u16();
      e.max_packet = w_max & 0x07FF;
      e.interval = c.u8();
      expect((e.address & 0x70) == 0 && (e.address & 0x0F) != 0,
             "endpoint descriptor" + where + ": bEndpointAddress " + hex(e.address) +
                 " (reserved bits set or endpoint 0)");
      cfg.interfaces.back().endpoints.push_back(e);
    } else {
      fail("descriptor type " + hex(type) + where + " is not one this device should have");
    }
  }
  std::set<std::uint8_t> numbers;
  for (std::size_t k = 0; k < cfg.interfaces.size(); ++k) {
    numbers.insert(cfg.interfaces[k].number);
    expect(cfg.interfaces[k].endpoints.size() == declared_endpoints[k],
           "interface " + std::to_string(cfg.interfaces[k].number) + ": bNumEndpoints " +
               std::to_string(declared_endpoints[k]) + " but " +
               std::to_string(cfg.interfaces[k].endpoints.size()) + " endpoint descriptors follow");
  }
  expect(numbers.size() == cfg.num_interfaces,
         "configuration: bNumInterfaces " + std::to_string(cfg.num_interfaces) + " but " +
             std::to_string(numbers.size()) + " interface numbers present");
  return cfg;
}

std::vector<std::uint16_t> decode_langids(Bytes b) {
  // facts §1.8: bLength, 0x03, wLANGID[]
  Cursor c(b, "string descriptor 0");
  const std::uint8_t length = c.u8();
  expect(length == b.size(), "string descriptor 0: bLength does not match its size");
  expect(c.u8() == kString, "string descriptor 0: bDescriptorType is not 0x03");
  expect(length >= 4 && length % 2 == 0, "string descriptor 0: no whole LANGID");
  std::vector<std::uint16_t> ids;
  while (c.at() < c.size()) ids.push_back(c.u16());
  return ids;
}

std::string decode_string(Bytes b) {
  // facts §1.8: bLength = 2 + 2 * chars, 0x03, UTF-16LE, no terminating NUL
  Cursor c(b, "string descriptor");
  const std::uint8_t length = c.u8();
  expect(length == b.size(), "string descriptor: bLength " + std::to_string(length) +
                                 " but " + std::to_string(b.size()) + " bytes");
  expect(c.u8() == kString, "string descriptor: bDescriptorType is not 0x03");
  expect(length % 2 == 0, "string descriptor: odd bLength (half a UTF-16 unit)");
  std::u16string text;
  while (c.at() < c.size()) {
    const char16_t unit = c.u16();
    expect(unit != 0, "string descriptor: a NUL code unit (strings carry no terminator)");
    expect(unit < 0xD800 || unit > 0xDFFF, "string descriptor: a surrogate code unit");
    text.push_back(unit);
  }
  return to_utf8(text);
}

std::string to_utf8(const std::u16string& s) {
  std::string out;
  for (const char16_t u : s) {
    if (u < 0x80) {
      out.push_back(static_cast<char>(u));
    } else if (u < 0x800) {
      out.push_back(static_cast<char>(0xC0 | (u >> 6)));
      out.push_back(static_cast<char>(0x80 | (u & 0x3F)));
    } else {
      out.push_back(static_cast<char>(0xE0 | (u >> 12)));
      out.push_back(static_cast<char>(0x80 | ((u >> 6) & 0x3F)));
      out.push_back(static_cast<char>(0x80 | (u & 0x3F)));
    }
  }
  return out;
}

std::vector<HidItem> decode_hid_items(Bytes b) {
  // facts §2.3: prefix = tag << 4 | type << 2 | size code (1/2/3 = 1/2/4 data bytes)
  Cursor c(b, "HID report descriptor");
  std::vector<HidItem> items;
  while (c.at() < c.size()) {
    const std::uint8_t prefix = c.u8();
    expect(prefix != 0xFE, "HID report descriptor: long item (not used by this device)");
    HidItem item;
    item.type = (prefix >> 2) & 0x3;
    item.tag = prefix >> 4;
    expect(item.type != 3, "HID report descriptor: reserved item type at offset " +
                               std::to_string(c.at() - 1));
    static constexpr std::uint8_t kSizes[4] = {0, 1, 2, 4};
    item.size = kSizes[prefix & 0x3];
    for (std::uint8_t k = 0; k < item.size; ++k)
      item.data |= static_cast<std::uint32_t>(c.u8()) << (8 * k);
    items.push_back(item);
  }
  return items;
}

HidReports summarise_hid_report(Bytes b) {
  // HID 1.11 item tags (facts §2.3's table): main 8 Input, 9 Output, 0xA Collection,
  // 0xB Feature, 0xC End Collection; global 0 Usage Page, 1/2 Logical Min/Max, 7 Report Size,
  // 8 Report ID, 9 Report Count
  const auto signed_value = [](const HidItem& i) -> std::int64_t {
    if (i.size == 1) return static_cast<std::int8_t>(i.data);
    if (i.size == 2) return static_cast<std::int16_t>(i.data);
    return static_cast<std::int32_t>(i.data);
  };
  HidReports r;
  std::uint32_t report_size = 0, report_count = 0;
  std::int64_t logical_min = 0, logical_max = 0;
  for (const HidItem& i : decode_hid_items(b)) {
    if (i.type == 1) {
      switch (i.tag) {
        case 0: r.usage_page = i.data; break;
        case 1: logical_min = signed_value(i); break;
        case 2: logical_max = signed_value(i); break;
        case 7: report_size = i.data; break;
        case 8: r.report_id_declared = true; break;
        case 9: report_count = i.data; break;
        default: break;
      }
    } else if (i.type == 0) {
      switch (i.tag) {
        case 0x8: r.input_bits += report_size * report_count; break;
        case 0x9: r.output_bits += report_size * report_count; break;
        case 0xB: r.feature_bits += report_size * report_count; break;
        case 0xA: ++r.open_collections; break;
        case 0xC:
          expect(r.open_collections > 0, "HID report descriptor: End Collection without one open");
          --r.open_collections;
          break;
        default: fail("HID report descriptor: unknown main item tag " + hex(i.tag));
      }
      if (i.tag == 0x8 || i.tag == 0x9 || i.tag == 0xB) {
        r.logical_min = logical_min;
        r.logical_max = logical_max;
      }
    }
  }
  return r;
}

Bos decode_bos(Bytes b) {
  // facts §3: 5-byte header, then capabilities (bLength, 0x10, bDevCapabilityType, ...)
  Cursor c(b, "BOS");
  expect(c.u8() == 5, "BOS: bLength is not 5");
  expect(c.u8() == kBos, "BOS: bDescriptorType is not 0x0F");
  Bos bos;
  bos.total_length = c.u16();
  expect(bos.total_length == b.size(), "BOS: wTotalLength " + std::to_string(bos.total_length) +
                                           " but " + std::to_string(b.size()) + " bytes");
  bos.num_capabilities = c.u8();
  while (c.at() < c.size()) {
    const std::size_t start = c.at();
    const std::uint8_t length = c.peek(0);
    expect(length >= 3 && start + length <= b.size(),
           "BOS capability at offset " + std::to_string(start) + ": bLength runs past the BOS");
    c.u8();
    expect(c.u8() == kCapability, "BOS capability at offset " + std::to_string(start) +
                                      ": bDescriptorType is not 0x10");
    const std::uint8_t type = c.u8();
    bos.capability_types.push_back(type);
    if (type == 0x05) {  // platform: bReserved, UUID[16], CapabilityData
      expect(length >= 20, "platform capability shorter than 20 bytes");
      expect(c.u8() == 0, "platform capability: bReserved is not 0");
      PlatformCapability p;
      for (auto& byte : p.uuid) byte = c.u8();
      while (c.at() < start + length) p.data.push_back(c.u8());
      bos.platform.push_back(p);
    }
    c.seek(start + length);
  }
  expect(bos.capability_types.size() == bos.num_capabilities,
         "BOS: bNumDeviceCaps " + std::to_string(bos.num_capabilities) + " but " +
             std::to_string(bos.capability_types.size()) + " capabilities present");
  return bos;
}

std::array<std::uint8_t, 16> guid_bytes(const std::string& g) {
  // {AAAAAAAA-BBBB-CCCC-DDDD-EEEEEEEEEEEE}: A, B, C little-endian, D and E as written (facts §4.1)
  expect(g.size() == 38 && g.front() == '{' && g.back() == '}' && g[9] == '-' && g[14] == '-' &&
             g[19] == '-' && g[24] == '-',
         "not a braced GUID: " + g);
  const auto byte_at = [&](std::size_t pos) {
    return static_cast<std::uint8_t>(std::stoul(g.substr(pos, 2), nullptr, 16));
  };
  std::array<std::uint8_t, 16> out{};
  for (int k = 0; k < 4; ++k) out[k] = byte_at(1 + 2 * (3 - k));
  for (int k = 0; k < 2; ++k) out[4 + k] = byte_at(10 + 2 * (1 - k));
  for (int k = 0; k < 2; ++k) out[6 + k] = byte_at(15 + 2 * (1 - k));
  for (int k = 0; k < 2; ++k) out[8 + k] = byte_at(20 + 2 * k);
  for (int k = 0; k < 6; ++k) out[10 + k] = byte_at(25 + 2 * k);
  return out;
}

MsOs20Capability decode_ms_os_20_capability(const PlatformCapability& cap) {
  // facts §4.1: offsets 20..27 of the capability = CapabilityData 0..7
  expect(cap.data.size() == 8, "MS OS 2.0 capability data is " + std::to_string(cap.data.size()) +
                                   " bytes, not 8 (bLength 28)");
  Cursor c(cap.data, "MS OS 2.0 capability data");
  MsOs20Capability m;
  m.windows_version = c.u32();
  m.set_total_length = c.u16();
  m.vendor_code = c.u8();
  m.alt_enum_code = c.u8();
  return m;
}

namespace {

// facts §4.2 record types
constexpr std::uint16_t kSetHeader = 0, kConfigSubset = 1, kFunctionSubset = 2,
                        kCompatibleId = 3, kRegistryProperty = 4;

std::u16string read_utf16(Cursor& c, std::size_t bytes) {
  std::u16string s;
  for (std::size_t k = 0; k < bytes / 2; ++k) s.push_back(static_cast<char16_t>(c.u16()));
  return s;
}

MsFeature read_feature(Cursor& c, std::uint16_t length, std::uint16_t type, std::size_t start) {
  const std::string where = " at offset " + std::to_string(start);
  MsFeature f;
  f.type = type;
  if (type == kCompatibleId) {
    // facts §4.3: 20 bytes: wLength, wDescriptorType, CompatibleID[8], SubCompatibleID[8]
    expect(length == 20, "compatible ID" + where + ": wLength " + std::to_string(length) +
                             ", not 20");
    for (int k = 0; k < 8; ++k)
      if (const std::uint8_t ch = c.u8(); ch != 0) f.compatible_id.push_back(static_cast<char>(ch));
    for (int k = 0; k < 8; ++k)
      if (const std::uint8_t ch = c.u8(); ch != 0)
        f.sub_compatible_id.push_back(static_cast<char>(ch));
  } else if (type == kRegistryProperty) {
    // facts §4.3: wLength, wDescriptorType, wPropertyDataType, wPropertyNameLength,
    // PropertyName, wPropertyDataLength, PropertyData; wLength = 10 + name + data
    f.property_data_type = c.u16();
    const std::uint16_t name_length = c.u16();
    expect(name_length % 2 == 0 && name_length >= 2,
           "registry property" + where + ": odd or empty wPropertyNameLength");
    std::u16string name = read_utf16(c, name_length);
    expect(name.back() == u'\0', "registry property" + where + ": name not NUL-terminated");
    name.pop_back();
    f.property_name = name;
    const std::uint16_t data_length = c.u16();
    expect(length == 10 + name_length + data_length,
           "registry property" + where + ": wLength " + std::to_string(length) + " but 10 + " +
               std::to_string(name_length) + " + " + std::to_string(data_length));
    expect(data_length % 2 == 0, "registry property" + where + ": odd wPropertyDataLength");
    const std::u16string data = read_utf16(c, data_length);
    f.multi_sz_terminated = data.size() >= 2 && data[data.size() - 1] == u'\0' &&
                            data[data.size() - 2] == u'\0';
    std::u16string entry;
    for (const char16_t u : data) {
      if (u == u'\0') {
        if (!entry.empty()) f.property_strings.push_back(entry);
        entry.clear();
      } else {
        entry.push_back(u);
      }
    }
    expect(entry.empty(), "registry property" + where + ": data not NUL-terminated");
  }
  c.seek(start + length);
  return f;
}

/// Records from c's position up to end, placed by kind; nesting follows facts §4.2.
void read_records(Cursor& c, std::size_t end, MsOs20Set& set, MsConfiguration* cfg,
                  MsFunction* fn) {
  while (c.at() < end) {
    const std::size_t start = c.at();
    const std::string where = " at offset " + std::to_string(start);
    expect(start + 4 <= end, "MS OS 2.0 record" + where + " cut by its subset's end");
    const std::uint16_t length = c.u16(), type = c.u16();
    expect(length >= 4 && start + length <= end,
           "MS OS 2.0 record" + where + ": wLength " + std::to_string(length) +
               " runs past its subset");
    if (type == kSetHeader) fail("a second set header" + where);
    if (type == kConfigSubset) {
      expect(cfg == nullptr, "configuration subset" + where + " inside another subset");
      expect(length == 8, "configuration subset header" + where + ": wLength is not 8");
      MsConfiguration next;
      next.configuration = c.u8();
      expect(c.u8() == 0, "configuration subset header" + where + ": bReserved is not 0");
      const std::uint16_t total = c.u16();
      expect(total >= 8 && start + total <= end,
             "configuration subset" + where + ": wTotalLength " + std::to_string(total) +
                 " runs past the set");
      read_records(c, start + total, set, &next, nullptr);
      set.configurations.push_back(next);
    } else if (type == kFunctionSubset) {
      expect(cfg != nullptr && fn == nullptr,
             "function subset" + where + " outside a configuration subset");
      expect(length == 8, "function subset header" + where + ": wLength is not 8");
      MsFunction next;
      next.first_interface = c.u8();
      expect(c.u8() == 0, "function subset header" + where + ": bReserved is not 0");
      const std::uint16_t total = c.u16();
      expect(total >= 8 && start + total <= end,
             "function subset" + where + ": wSubsetLength " + std::to_string(total) +
                 " runs past its configuration subset");
      read_records(c, start + total, set, cfg, &next);
      cfg->functions.push_back(next);
    } else {
      MsFeature f = read_feature(c, length, type, start);
      if (fn != nullptr) fn->features.push_back(f);
      else if (cfg != nullptr) cfg->features.push_back(f);
      else set.device_features.push_back(f);
    }
  }
  expect(c.at() == end, "MS OS 2.0 records overrun their subset's end");
}

}  // namespace

MsOs20Set decode_ms_os_20_set(Bytes b) {
  // facts §4.3: set header 10 bytes: wLength, wDescriptorType 0, dwWindowsVersion, wTotalLength
  Cursor c(b, "MS OS 2.0 set");
  expect(c.u16() == 10, "MS OS 2.0 set header: wLength is not 10");
  expect(c.u16() == kSetHeader, "MS OS 2.0 set: does not begin with the set header");
  MsOs20Set set;
  set.windows_version = c.u32();
  set.total_length = c.u16();
  expect(set.total_length == b.size(), "MS OS 2.0 set: wTotalLength " +
                                           std::to_string(set.total_length) + " but " +
                                           std::to_string(b.size()) + " bytes");
  read_records(c, b.size(), set, nullptr, nullptr);
  return set;
}

namespace {
template <class Pick>
std::vector<int> where_feature(const MsOs20Set& set, Pick pick) {
  std::vector<int> out;
  for (const MsFeature& f : set.device_features)
    if (pick(f)) out.push_back(-1);
  for (const MsConfiguration& cfg : set.configurations) {
    for (const MsFeature& f : cfg.features)
      if (pick(f)) out.push_back(-1);
    for (const MsFunction& fn : cfg.functions)
      for (const MsFeature& f : fn.features)
        if (pick(f)) out.push_back(fn.first_interface);
  }
  return out;
}
}  // namespace

std::vector<int> interfaces_with_compatible_id(const MsOs20Set& set, const std::string& id) {
  return where_feature(set, [&](const MsFeature& f) {
    return f.type == kCompatibleId && f.compatible_id == id;
  });
}
std::vector<int> interfaces_with_property(const MsOs20Set& set, const std::string& name) {
  return where_feature(set, [&](const MsFeature& f) {
    return f.type == kRegistryProperty && to_utf8(f.property_name) == name;
  });
}

}  // namespace palp::test::usbdec
