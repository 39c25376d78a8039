// SPDX-License-Identifier: Apache-2.0
// Host-only text helpers for the protocol: hex, field printing, message decoding to text.
#pragma once

#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "palp/protocol/codec.hpp"

namespace palp::proto {

/// Lower-case hex bytes separated by single spaces: "0a 01 ff".
std::string to_hex(std::span<const u8> bytes);
/// Parses hex bytes; whitespace between bytes is optional. nullopt on any other character or an
/// odd number of digits, with the reason in *error when given ("character 7 'g' is not a hex
/// digit", "a lone hex digit at character 3").
std::optional<std::vector<u8>> parse_hex(std::string_view text, std::string* error = nullptr);

namespace detail {
std::string format_scalar(double v, bool is_float);
std::string format_text_field(const char* bytes, std::size_t n);

template <class T>
std::string format_value(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    const char* n = enum_name(value);
    if (n != nullptr) return n;
    return std::to_string(static_cast<u32>(value)) + " (unknown)";
  } else if constexpr (std::is_same_v<T, f32>) {
    return format_scalar(value, true);
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else if constexpr (requires { value.bytes; }) {
    return format_text_field(value.bytes.data(), value.bytes.size());
  } else {
    std::string s = "[";
    bool first = true;
    for (const auto& x : value) {
      if (!first) s += ", ";
      s += format_value(x);
      first = false;
    }
    return s + "]";
  }
}
}  // namespace detail

/// One "name = value" line per field, in catalogue order, each prefixed by `prefix`.
template <class M>
std::string format_fields(const M& m, std::string_view prefix = "field ") {
  std::string out;
  m.visit([&](const FieldInfo& f, const auto& value) {
    out += prefix;
    out += f.name;
    out += " = ";
    out += detail::format_value(value);
    out += '\n';
  });
  return out;
}

/// Decodes a payload of message `id` and prints "Name" and its fields; or the reject reason.
std::string describe_payload(u8 id, std::span<const u8> payload);

}  // namespace palp::proto
