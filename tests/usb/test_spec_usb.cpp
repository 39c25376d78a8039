// SPDX-License-Identifier: Apache-2.0
// protocol/SPEC.md §3.1 states what the device serves: the HID report descriptor's bytes, the
// MS OS 2.0 vendor code and the DeviceInterfaceGUID there are the firmware's (a change to either
// side without the other fails here).
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "palp/usb/descriptors.hpp"

namespace {

std::string spec_section_3_1() {
  std::ifstream f(PALP_SOURCE_DIR "/protocol/SPEC.md");
  const std::string spec((std::istreambuf_iterator<char>(f)), {});
  const auto from = spec.find("### 3.1 USB identity and endpoints");
  const auto to = spec.find("\n## 4.", from);
  EXPECT_NE(from, std::string::npos) << "SPEC.md has no §3.1";
  return from == std::string::npos ? "" : spec.substr(from, to - from);
}

/// The bytes of the code block after "**HID report layout.**": each line's leading two-digit hex
/// tokens, up to its first other word.
std::vector<std::uint8_t> spec_hid_report_bytes(const std::string& section) {
  std::vector<std::uint8_t> out;
  const auto para = section.find("**HID report layout.**");
  const auto open = section.find("```", para);
  const auto close = section.find("```", open + 3);
  if (para == std::string::npos || open == std::string::npos || close == std::string::npos) {
    ADD_FAILURE() << "no HID report block in SPEC §3.1";
    return out;
  }
  std::istringstream lines(section.substr(open + 3, close - open - 3));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    for (std::string w; words >> w;) {
      if (w.size() != 2 || !std::isxdigit(static_cast<unsigned char>(w[0])) ||
          !std::isxdigit(static_cast<unsigned char>(w[1])))
        break;
      out.push_back(static_cast<std::uint8_t>(std::stoul(w, nullptr, 16)));
    }
  }
  return out;
}

TEST(UsbSpec, HidReportBytesInSpecAreTheServedReportDescriptor) {
  const auto served = palp::usb::find_descriptor(0x22, 0, 1);
  EXPECT_EQ(spec_hid_report_bytes(spec_section_3_1()),
            std::vector<std::uint8_t>(served.begin(), served.end()));
}

TEST(UsbSpec, SpecNamesTheFirmwaresVendorCodeGuidAndSetLength) {
  const std::string section = spec_section_3_1();
  char code[32];
  std::snprintf(code, sizeof code, "bRequest `0x%02X`", palp::usb::kMsOs20VendorCode);
  EXPECT_NE(section.find(code), std::string::npos) << code;
  EXPECT_NE(section.find(palp::usb::kDeviceInterfaceGuid), std::string::npos);
  EXPECT_NE(section.find("wMSOSDescriptorSetTotalLength " +
                         std::to_string(palp::usb::ms_os_20_descriptor_set().size())),
            std::string::npos);
  EXPECT_NE(section.find("wIndex `0x0007`"), std::string::npos);
}

}  // namespace
