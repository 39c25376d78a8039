// SPDX-License-Identifier: Apache-2.0
// The termios speeds serial:// accepts: POSIX's, then Linux's higher ones where defined.
#include "transport/serial_speeds.hpp"

#include <array>
#include <span>

#include "palp/transport.hpp"

namespace palp {
namespace {

struct SerialSpeed {
  std::uint32_t baud;
  speed_t speed;
};

constexpr SerialSpeed kSerialSpeeds[] = {
    {50, B50},           {75, B75},           {110, B110},         {134, B134},
    {150, B150},         {200, B200},         {300, B300},         {600, B600},
    {1200, B1200},       {1800, B1800},       {2400, B2400},       {4800, B4800},
    {9600, B9600},       {19200, B19200},     {38400, B38400},     {57600, B57600},
    {115200, B115200},   {230400, B230400},
#ifdef B4000000
    {460800, B460800},   {500000, B500000},   {576000, B576000},   {921600, B921600},
    {1000000, B1000000}, {1152000, B1152000}, {1500000, B1500000}, {2000000, B2000000},
    {2500000, B2500000}, {3000000, B3000000}, {3500000, B3500000}, {4000000, B4000000},
#endif
};

constexpr std::size_t kSerialSpeedCount = std::size(kSerialSpeeds);

constexpr std::array<std::uint32_t, kSerialSpeedCount> baud_column() {
  std::array<std::uint32_t, kSerialSpeedCount> b{};
  for (std::size_t k = 0; k < kSerialSpeedCount; ++k) b[k] = kSerialSpeeds[k].baud;
  return b;
}
constexpr std::array<std::uint32_t, kSerialSpeedCount> kSerialBauds = baud_column();

}  // namespace

std::span<const std::uint32_t> serial_bauds() { return kSerialBauds; }

namespace detail {

std::optional<speed_t> termios_speed(std::uint32_t baud) {
  for (const SerialSpeed& s : kSerialSpeeds)
    if (s.baud == baud) return s.speed;
  return std::nullopt;
}

std::string unsupported_baud(std::uint32_t baud) {
  std::string t;
  for (const std::uint32_t b : kSerialBauds) t += (t.empty() ? "" : ", ") + std::to_string(b);
  return "baud " + std::to_string(baud) + " is not a termios speed (supported: " + t + ")";
}

}  // namespace detail
}  // namespace palp
