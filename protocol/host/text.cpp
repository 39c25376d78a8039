// SPDX-License-Identifier: Apache-2.0
#include "palp/protocol/text.hpp"

#include <cmath>

namespace palp::proto {

std::string to_hex(std::span<const u8> bytes) {
  static constexpr char digits[] = "0123456789abcdef";
  std::string s;
  s.reserve(bytes.size() * 3);
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    if (k != 0) s += ' ';
    s += digits[bytes[k] >> 4];
    s += digits[bytes[k] & 0xF];
  }
  return s;
}

std::optional<std::vector<u8>> parse_hex(std::string_view text, std::string* error) {
  std::vector<u8> out;
  int hi = -1;
  const auto fail = [&](std::string why) -> std::optional<std::vector<u8>> {
    if (error != nullptr) *error = std::move(why);
    return std::nullopt;
  };
  for (std::size_t pos = 0; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      if (hi >= 0) return fail("a lone hex digit at character " + std::to_string(pos));
      continue;
    }
    int v;
    if (c >= '0' && c <= '9') v = c - '0';
    else if (c >= 'a' && c <= 'f') v = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
    else return fail("character " + std::to_string(pos + 1) + " '" + std::string(1, c) +
                     "' is not a hex digit");
    if (hi < 0) {
      hi = v;
    } else {
      out.push_back(static_cast<u8>(hi * 16 + v));
      hi = -1;
    }
  }
  if (hi >= 0) return fail("a lone hex digit at the end");
  return out;
}

namespace detail {
std::string format_scalar(double v, bool is_float) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, is_float ? "%.9g" : "%.17g", v);
  return buf;
}

std::string format_text_field(const char* bytes, std::size_t n) {
  std::size_t len = 0;
  while (len < n && bytes[len] != '\0') ++len;
  std::string s = "\"";
  for (std::size_t k = 0; k < len; ++k) {
    const unsigned char c = static_cast<unsigned char>(bytes[k]);
    if (c == '"' || c == '\\') {
      s += '\\';
      s += static_cast<char>(c);
    } else if (c < 0x20 || c >= 0x7F) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\x%02x", c);
      s += esc;
    } else {
      s += static_cast<char>(c);
    }
  }
  return s + "\"";
}
}  // namespace detail

std::string describe_payload(u8 id, std::span<const u8> payload) {
  std::string out;
  const Reject r = decode_message(id, payload.data(), payload.size(), [&](const auto& m) {
    out = std::string(std::decay_t<decltype(m)>::kName) + "\n" + format_fields(m, "  ");
  });
  if (r != Reject::ok) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "rejected (%s), message id 0x%02x\n", reject_name(r), id);
    return buf;
  }
  return out;
}

}  // namespace palp::proto
