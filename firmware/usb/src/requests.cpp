// SPDX-License-Identifier: Apache-2.0
#include "palp/usb/requests.hpp"

#include "palp/protocol/usb.hpp"

namespace palp::usb {

SetupPacket parse_setup(const std::uint8_t* bytes) {
  const auto word = [bytes](int at) {
    return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
  };
  return SetupPacket{bytes[0], bytes[1], word(2), word(4), word(6)};
}

std::size_t hid_report_take(const std::uint8_t* bytes, std::size_t pending) {
  constexpr std::size_t kReport = proto::usb::kHidReportSize;
  if (pending >= kReport) return kReport;
  for (std::size_t k = pending; k > 0; --k)
    if (bytes[k - 1] == 0x00) return k;
  return 0;
}

}  // namespace palp::usb
