// SPDX-License-Identifier: Apache-2.0
// URI parsing for the transports (transport.hpp).
#include <charconv>
#include <string_view>

#include "palp/error.hpp"
#include "palp/transport.hpp"
#include "transport/serial_speeds.hpp"

namespace palp {
namespace {

[[noreturn]] void bad(const std::string& text, const std::string& why) {
  throw ConfigError("transport URI '" + text + "': " + why +
                    " (expected tcp://host:port, serial:///dev/ttyX[?baud=N], usb://[serial], "
                    "hid://[serial], sim://host:port, sim:///path/to/socket or "
                    "sim+inproc://phantom[?key=value&...])");
}

std::uint16_t parse_u16(const std::string& text, std::string_view v, const char* what) {
  int base = 10;
  if (v.size() > 2 && v[0] == '0' && (v[1] == 'x' || v[1] == 'X')) {
    v.remove_prefix(2);
    base = 16;
  }
  unsigned value = 0;
  const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), value, base);
  if (ec != std::errc{} || p != v.data() + v.size() || v.empty() || value > 0xFFFF)
    bad(text, std::string(what) + " '" + std::string(v) + "' is not a number from 0 to 65535");
  return static_cast<std::uint16_t>(value);
}

/// host:port after scheme:// (sim://, tcp://) into u.host and u.port.
void parse_host_port(const std::string& text, const std::string& scheme, const std::string& rest,
                     Uri& u) {
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0) bad(text, scheme + ":// needs host:port");
  u.host = rest.substr(0, colon);
  u.port = parse_u16(text, std::string_view(rest).substr(colon + 1), "port");
  if (u.port == 0) bad(text, "port 0 is not a port to connect to");
}

std::uint32_t parse_baud(const std::string& text, std::string_view v) {
  std::uint32_t baud = 0;
  const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), baud);
  if (ec != std::errc{} || p != v.data() + v.size() || v.empty())
    bad(text, "baud '" + std::string(v) + "' is not a number");
  if (!detail::termios_speed(baud)) bad(text, detail::unsupported_baud(baud));
  return baud;
}

/// Calls f(key, value) for each key=value of a query ("a=1&b=2").
template <class F>
void for_each_parameter(const std::string& text, std::string_view query, F&& f) {
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view kv = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    const std::size_t eq = kv.find('=');
    if (eq == std::string_view::npos) bad(text, "parameter '" + std::string(kv) + "' has no value");
    f(kv.substr(0, eq), kv.substr(eq + 1));
  }
}

}  // namespace

Uri parse_uri(const std::string& text) {
  Uri u;
  u.text = text;
  const std::size_t sep = text.find("://");
  if (sep == std::string::npos) bad(text, "no scheme");
  const std::string scheme = text.substr(0, sep);
  std::string rest = text.substr(sep + 3);
  if (scheme == "sim" || scheme == "tcp") {
    if (scheme == "sim" && !rest.empty() && rest[0] == '/') {
      u.scheme = Uri::Scheme::sim_unix;
      u.path = rest;
      return u;
    }
    u.scheme = scheme == "sim" ? Uri::Scheme::sim_tcp : Uri::Scheme::tcp;
    parse_host_port(text, scheme, rest, u);
    return u;
  }
  if (scheme == "serial") {
    u.scheme = Uri::Scheme::serial;
    const std::size_t q = rest.find('?');
    u.path = rest.substr(0, q);
    if (u.path.size() < 2 || u.path[0] != '/')
      bad(text, "serial:// needs the tty's absolute path (serial:///dev/ttyUSB0)");
    if (q != std::string::npos)
      for_each_parameter(text, std::string_view(rest).substr(q + 1),
                         [&](std::string_view key, std::string_view value) {
                           if (key == "baud") u.baud = parse_baud(text, value);
                           else bad(text, "unknown parameter '" + std::string(key) +
                                              "' (known: baud)");
                         });
    return u;
  }
  if (scheme == "sim+inproc") {
    u.scheme = Uri::Scheme::sim_inproc;
    const std::size_t q = rest.find('?');
    u.phantom = rest.substr(0, q);
    if (u.phantom.empty())
      bad(text, "sim+inproc:// needs a phantom name: sim+inproc://none for free air, or one "
                "palp-sim --help lists");
    if (q != std::string::npos)
      for_each_parameter(text, std::string_view(rest).substr(q + 1),
                         [&](std::string_view key, std::string_view value) {
                           u.parameters.emplace_back(std::string(key), std::string(value));
                         });
    return u;
  }
  if (scheme != "usb" && scheme != "hid") bad(text, "unknown scheme '" + scheme + "'");
  u.scheme = scheme == "usb" ? Uri::Scheme::usb : Uri::Scheme::hid;
  const std::size_t q = rest.find('?');
  std::string query;
  if (q != std::string::npos) {
    query = rest.substr(q + 1);
    rest = rest.substr(0, q);
  }
  if (rest.find('/') != std::string::npos) bad(text, "a serial number has no '/'");
  u.serial = rest;
  for_each_parameter(text, query, [&](std::string_view key, std::string_view value) {
    if (key == "vid") u.vid = parse_u16(text, value, "vid");
    else if (key == "pid") u.pid = parse_u16(text, value, "pid");
    else bad(text, "unknown parameter '" + std::string(key) + "' (known: vid, pid)");
  });
  return u;
}

}  // namespace palp
