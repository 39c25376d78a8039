// SPDX-License-Identifier: Apache-2.0
// The firmware's standard descriptors decoded by a second, outside reader: Debian's tshark
// (Wireshark's USB dissector) reads a synthesised usbmon capture of the enumeration (the requests
// a Linux host makes, answered by find_descriptor) and the test compares the fields it prints
// with known answers from usb.hpp and SPEC.md §3.1.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <unistd.h>
#include <string>
#include <vector>

#include "palp/usb/descriptors.hpp"
#include "usbmon_pcap.hpp"

#ifndef PALP_TSHARK
#define PALP_TSHARK ""
#endif

namespace {

using palp::test::SetupPacket;

std::vector<std::uint8_t> reply(const SetupPacket& s) {
  const auto d = palp::usb::find_descriptor(static_cast<std::uint8_t>(s.value >> 8),
                                            static_cast<std::uint8_t>(s.value & 0xFF), s.index);
  const std::size_t n = d.size() < s.length ? d.size() : s.length;  // at most wLength
  return {d.begin(), d.begin() + static_cast<std::ptrdiff_t>(n)};
}

/// The enumeration after SET_ADDRESS, as frames 1.. of the capture (two per transfer).
std::vector<SetupPacket> enumeration() {
  std::vector<SetupPacket> r;
  r.push_back({0x80, 0x06, 0x0100, 0, 18});      // frames 1, 2: device
  r.push_back({0x80, 0x06, 0x0200, 0, 9});       // 3, 4: configuration header
  r.push_back({0x80, 0x06, 0x0200, 0, 255});     // 5, 6: whole configuration
  r.push_back({0x80, 0x06, 0x0300, 0, 255});     // 7, 8: LANGID list
  for (std::uint16_t i = 1; i <= 5; ++i)         // 9 .. 18: strings 1..5
    r.push_back({0x80, 0x06, static_cast<std::uint16_t>(0x0300 | i), 0x0409, 255});
  r.push_back({0x81, 0x06, 0x2200, 1, 34});      // 19, 20: HID report descriptor
  return r;
}

/// One frame's fields as tshark prints them: each field's occurrences joined by ',' ("" when the
/// frame has none).
using Row = std::vector<std::string>;

/// Runs tshark on pcap and returns each frame's fields, by frame number.
std::map<int, Row> tshark_fields(const std::string& pcap, const std::vector<std::string>& fields) {
  const std::string errors = pcap + ".stderr";
  std::string cmd = std::string(PALP_TSHARK) + " -n -r '" + pcap +
                    "' -T fields -E separator='|' -E occurrence=a -E aggregator=, -e frame.number";
  for (const std::string& f : fields) cmd += " -e " + f;
  cmd += " 2>'" + errors + "'";
  std::map<int, Row> rows;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) {
    ADD_FAILURE() << "cannot run " << cmd;
    return rows;
  }
  std::string out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), p) != nullptr) out += buf.data();
  const int status = pclose(p);
  std::ifstream err_file(errors);
  const std::string err((std::istreambuf_iterator<char>(err_file)), {});
  std::filesystem::remove(errors);
  EXPECT_EQ(status, 0) << cmd << "\n" << err;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    Row cols;
    std::size_t from = 0;
    for (std::size_t bar; (bar = line.find('|', from)) != std::string::npos; from = bar + 1)
      cols.push_back(line.substr(from, bar - from));
    cols.push_back(line.substr(from));
    const int frame = std::atoi(cols[0].c_str());
    if (frame <= 0 || cols.size() != fields.size() + 1) {
      ADD_FAILURE() << "tshark printed: " << line;
      continue;
    }
    cols.erase(cols.begin());
    rows[frame] = cols;
  }
  return rows;
}

class UsbDescriptorsTshark : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::string(PALP_TSHARK).empty())
      GTEST_SKIP() << "tshark not found at configure time: scripts/install-deps installs it";
    palp::usb::set_serial_number("0032001A5734501020383438");
    palp::test::UsbmonPcap cap(1, 5);
    for (const SetupPacket& s : enumeration()) cap.control_in(s, reply(s));
    pcap_ = (std::filesystem::temp_directory_path() /
             ("palp_usb_enumeration_" + std::to_string(::getpid()) + ".pcap"))
                .string();
    ASSERT_TRUE(cap.write(pcap_)) << pcap_;
  }
  void TearDown() override {
    if (!pcap_.empty()) std::filesystem::remove(pcap_);
  }
  /// The fields of frame `frame` (a completion: even frames carry the descriptors).
  Row frame(int number, const std::vector<std::string>& fields) {
    const auto rows = tshark_fields(pcap_, fields);
    EXPECT_EQ(rows.size(), 2 * enumeration().size()) << "one row per usbmon record";
    const auto it = rows.find(number);
    if (it == rows.end()) {
      ADD_FAILURE() << "no frame " << number;
      return Row(fields.size());
    }
    return it->second;
  }
  std::string pcap_;
};

TEST_F(UsbDescriptorsTshark, DecodesTheDeviceDescriptorWithUsbHppIdentityAndBcdUsb0201) {
  EXPECT_EQ(frame(2, {"usb.bLength", "usb.bDescriptorType", "usb.bcdUSB", "usb.bDeviceClass",
                      "usb.bMaxPacketSize0", "usb.idVendor", "usb.idProduct", "usb.bcdDevice",
                      "usb.iManufacturer", "usb.iProduct", "usb.iSerialNumber",
                      "usb.bNumConfigurations"}),
            (Row{"18", "0x01", "0x0201", "0x00", "64", "0x1209", "0x0001", "0x0001", "1", "2", "3",
                 "1"}));
}

TEST_F(UsbDescriptorsTshark, DecodesTheConfigurationHeaderAndTheWholeBlock) {
  const std::vector<std::string> header{"usb.wTotalLength", "usb.bNumInterfaces",
                                        "usb.bConfigurationValue", "usb.configuration.bmAttributes",
                                        "usb.bMaxPower"};
  EXPECT_EQ(frame(4, header), (Row{"64", "2", "1", "0x80", "50"})) << "the 9-byte read";
  EXPECT_EQ(frame(6, header), (Row{"64", "2", "1", "0x80", "50"})) << "the whole block";
}

TEST_F(UsbDescriptorsTshark, DecodesBothInterfacesTheHidDescriptorAndTheFourEndpoints) {
  EXPECT_EQ(frame(6, {"usb.bInterfaceNumber", "usb.bAlternateSetting", "usb.bNumEndpoints",
                      "usb.bInterfaceClass", "usb.bInterfaceSubClass", "usb.bInterfaceProtocol",
                      "usb.iInterface", "usbhid.descriptor.hid.bcdHID",
                      "usbhid.descriptor.hid.bCountryCode",
                      "usbhid.descriptor.hid.wDescriptorLength"}),
            (Row{"0,1", "0,0", "2,2", "0xff,0x03", "0x00,0x00", "0x00,0x00", "4,5", "0x0111",
                 "0x00", "34"}));
  EXPECT_EQ(frame(6, {"usb.bEndpointAddress", "usb.bmAttributes", "usb.wMaxPacketSize",
                      "usb.bInterval"}),
            (Row{"0x01,0x81,0x02,0x82", "0x02,0x02,0x03,0x03", "64,64,64,64", "0,0,1,1"}));
}

TEST_F(UsbDescriptorsTshark, DecodesTheLangIdAndEveryStringAsUtf16Le) {
  EXPECT_EQ(frame(8, {"usb.wLANGID"}), Row{"0x0409"});
  const std::vector<std::string> expected{"palp", "palp probe controller",
                                          "0032001A5734501020383438", "palp byte stream (bulk)",
                                          "palp byte stream (HID)"};
  const auto rows = tshark_fields(pcap_, {"usb.bString"});
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const auto it = rows.find(static_cast<int>(10 + 2 * k));
    ASSERT_NE(it, rows.end());
    EXPECT_EQ(it->second, Row{expected[k]}) << "string " << k + 1;
  }
}

TEST_F(UsbDescriptorsTshark, DecodesTheHidReportAs64ByteInputAndOutputWithoutReportId) {
  EXPECT_EQ(frame(20, {"usbhid.item.local.usage", "usbhid.item.main.colltype",
                       "usbhid.item.global.log_min", "usbhid.item.global.log_max",
                       "usbhid.item.global.report_size", "usbhid.item.global.report_count",
                       "usbhid.item.global.report_id"}),
            (Row{"0x01,0x02,0x03", "0x01", "0,0", "255,255", "8,8", "64,64", ""}));
}

TEST_F(UsbDescriptorsTshark, FindsNothingMalformedOrUnusualInAnyFrame) {
  const auto rows = tshark_fields(pcap_, {"_ws.malformed", "_ws.expert.message"});
  EXPECT_EQ(rows.size(), 2 * enumeration().size());
  for (const auto& [number, row] : rows) EXPECT_EQ(row, (Row{"", ""})) << "frame " << number;
}

}  // namespace
