// SPDX-License-Identifier: Apache-2.0
// host/udev/70-palp.rules against protocol/include/palp/protocol/usb.hpp (one definition of the
// identities): the rules name exactly the controller (its USB node and its hidraw node) and the
// STM32 ROM bootloader, each with TAG+="uaccess", and no GROUP (plugdev is missing on Fedora and
// Arch), so the seat's user may open them on any of the three.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "palp/protocol/usb.hpp"

namespace {

namespace pu = palp::proto::usb;

struct Rule {
  std::string text;
  std::string subsystem;  ///< the SUBSYSTEM== match
  std::string vid, pid;   ///< from ATTR{} or ATTRS{} idVendor/idProduct matches
};

std::vector<Rule> read_rules() {
  std::ifstream f(PALP_SOURCE_DIR "/host/udev/70-palp.rules");
  EXPECT_TRUE(f.good()) << "host/udev/70-palp.rules not readable";
  std::vector<Rule> rules;
  const std::regex subsystem(R"re(SUBSYSTEM=="([^"]*)")re");
  const std::regex vid(R"re(ATTRS?\{idVendor\}=="([^"]*)")re");
  const std::regex pid(R"re(ATTRS?\{idProduct\}=="([^"]*)")re");
  for (std::string line; std::getline(f, line);) {
    if (line.empty() || line[0] == '#') continue;
    EXPECT_NE(line.back(), '\\') << "continued lines are not expected: " << line;
    Rule r{line, "", "", ""};
    std::smatch m;
    if (std::regex_search(line, m, subsystem)) r.subsystem = m[1];
    if (std::regex_search(line, m, vid)) r.vid = m[1];
    if (std::regex_search(line, m, pid)) r.pid = m[1];
    rules.push_back(r);
  }
  return rules;
}

/// As sysfs writes idVendor/idProduct: four lower-case hex digits.
std::string sysfs_hex(std::uint16_t v) {
  char s[5];
  std::snprintf(s, sizeof s, "%04x", v);
  return s;
}

TEST(UdevRules, NameTheControllerOnUsbAndHidrawAndTheRomBootloaderWithUsbHppIds) {
  std::set<std::tuple<std::string, std::string, std::string>> got;
  for (const Rule& r : read_rules()) got.insert({r.subsystem, r.vid, r.pid});
  const std::string vid = sysfs_hex(pu::kVendorId), pid = sysfs_hex(pu::kProductId);
  const std::set<std::tuple<std::string, std::string, std::string>> want{
      {"usb", vid, pid},
      {"hidraw", vid, pid},
      {"usb", sysfs_hex(pu::kStBootloaderVendorId), sysfs_hex(pu::kStBootloaderProductId)}};
  EXPECT_EQ(got, want);
  EXPECT_EQ(vid + ":" + pid, "1209:0001");  // SPEC.md §3.1
  EXPECT_EQ(sysfs_hex(pu::kStBootloaderVendorId) + ":" + sysfs_hex(pu::kStBootloaderProductId),
            "0483:df11");  // facts §5.1
}

TEST(UdevRules, EveryRuleTagsUaccessAndNamesNoGroup) {
  const std::vector<Rule> rules = read_rules();
  ASSERT_EQ(rules.size(), 3u);
  for (const Rule& r : rules) {
    EXPECT_NE(r.text.find("TAG+=\"uaccess\""), std::string::npos) << r.text;
    EXPECT_EQ(r.text.find("GROUP"), std::string::npos) << r.text;
    EXPECT_EQ(r.text.find("plugdev"), std::string::npos) << r.text;
  }
}

}  // namespace
