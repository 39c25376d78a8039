#include "palp/usb/device.hpp"

namespace palp::usb {

SetupPacket parse_setup(const std::uint8_t* bytes) {
  const auto word = [bytes](int at) {
    return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
  };
  return SetupPacket{bytes[0], bytes[1], word(2), word(4), word(6)};
}

}  // namespace palp::usb
