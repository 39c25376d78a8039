// SPDX-License-Identifier: Apache-2.0
// The schema hash (SPEC.md §7): CRC-32 of the catalogue's canonical text. The canonical text is
// written here once, over a sink, so the same code computes the hash at compile time (for the
// firmware and the SDK) and prints the text (for SPEC.md and third parties who recompute it).
//
// Canonical text, one line per item, each ending in "\n", in catalogue order:
//   palp-protocol <major>.<minor>
//   enum <Name> <type>
//    value <number> <name>
//   message <id as 0xHH> <Name> <h2d|d2h> since <minor> reply <Name|None>
//    field <kind><type>[<count>] <name> since <minor> default <text> range <lo> <hi> unit "<unit>"
// where kind is S, E, A, V or T and [<count>] appears for A, V and T only. Docs are not part of it.
#pragma once

#include "palp/protocol/crc32.hpp"
#include "palp/protocol/messages.hpp"

namespace palp::proto {

template <class Sink>
constexpr void write_number(Sink& s, u32 value) {
  char digits[10] = {};
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  while (n > 0) s.put(digits[--n]);
}
template <class Sink>
constexpr void write_text(Sink& s, const char* text) {
  for (; *text != '\0'; ++text) s.put(*text);
}
template <class Sink>
constexpr void write_hex2(Sink& s, u32 value) {
  constexpr const char* hex = "0123456789ABCDEF";
  write_text(s, "0x");
  s.put(hex[(value >> 4) & 0xF]);
  s.put(hex[value & 0xF]);
}

/// Writes the canonical text of this build's catalogue into s (s.put(char) per character).
template <class Sink>
constexpr void write_canonical_schema(Sink& s) {
  write_text(s, "palp-protocol ");
  write_number(s, kProtocolMajor);
  s.put('.');
  write_number(s, kProtocolMinor);
  s.put('\n');
  for_each_enum([&](auto info) {
    using I = decltype(info);
    write_text(s, "enum ");
    write_text(s, I::name);
    s.put(' ');
    write_text(s, I::type);
    s.put('\n');
    for (const auto& v : I::values) {
      write_text(s, " value ");
      write_number(s, v.value);
      s.put(' ');
      write_text(s, v.name);
      s.put('\n');
    }
  });
  for (const MessageInfo& m : kMessages) {
    write_text(s, "message ");
    write_hex2(s, static_cast<u32>(m.id));
    s.put(' ');
    write_text(s, m.name);
    write_text(s, m.direction == Direction::H2D ? " h2d since " : " d2h since ");
    write_number(s, m.since);
    write_text(s, " reply ");
    write_text(s, m.reply == MessageId::None ? "None" : message_name(m.reply));
    s.put('\n');
    for (std::size_t k = 0; k < m.field_count; ++k) {
      const FieldInfo& f = m.fields[k];
      write_text(s, " field ");
      s.put(f.kind);
      write_text(s, f.type);
      if (f.kind == 'A' || f.kind == 'V' || f.kind == 'T') {
        s.put('[');
        write_number(s, f.count);
        s.put(']');
      }
      s.put(' ');
      write_text(s, f.name);
      write_text(s, " since ");
      write_number(s, f.since);
      write_text(s, " default ");
      write_text(s, f.default_text);
      write_text(s, " range ");
      write_text(s, f.lo_text);
      s.put(' ');
      write_text(s, f.hi_text);
      write_text(s, " unit \"");
      write_text(s, f.unit);
      write_text(s, "\"\n");
    }
  }
}

namespace detail {
struct CrcSink {
  u32 state = kCrc32Init;
  constexpr void put(char c) { state = crc32_update(state, c); }
};
constexpr u32 compute_schema_hash() {
  CrcSink s;
  write_canonical_schema(s);
  return crc32_final(s.state);
}
}  // namespace detail

/// This build's schema hash, computed by the compiler from the catalogue.
inline constexpr u32 kSchemaHash = detail::compute_schema_hash();

}  // namespace palp::proto
