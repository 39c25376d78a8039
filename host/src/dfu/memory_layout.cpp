// SPDX-License-Identifier: Apache-2.0
// The DfuSe memory-layout string (usb-dfu-facts.md §5.8):
//   @<name>/0x<start>/<N>*<size><mult><type>[,<N>*<size><mult><type>...][/0x<start>/...]
// mult: B (or a space) bytes, K x1024, M x1024^2; type letter: (letter & 7) bit 1 readable,
// bit 2 erasable, bit 4 writable ('a'..'g'). Each segment's size is its erase page size.
#include <cctype>
#include <cstdlib>

#include "dfu/dfu_messages.hpp"
#include "palp/dfu.hpp"

namespace palp::dfu {

namespace {

[[noreturn]] void bad_layout(std::string_view text, const std::string& why) {
  throw DfuseError(DfuseError::Kind::bad_layout,
                   "the device's memory-layout string \"" + std::string(text) +
                       "\" cannot be read: " + why +
                       "; is this an STM32 ROM bootloader (0483:df11)? dfu-util -l lists it");
}

// Reads an unsigned number (base 10, or 16 after 0x) at text[pos]; advances pos.
std::uint64_t read_number(std::string_view text, std::size_t& pos, bool hex, const char* what) {
  const std::size_t first = pos;
  std::uint64_t v = 0;
  while (pos < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[pos]);
    int digit = -1;
    if (std::isdigit(c)) digit = c - '0';
    else if (hex && std::isxdigit(c)) digit = std::tolower(c) - 'a' + 10;
    if (digit < 0) break;
    v = v * (hex ? 16 : 10) + static_cast<unsigned>(digit);
    if (v > 0xFFFFFFFFull) bad_layout(text, std::string(what) + " too large");
    ++pos;
  }
  if (pos == first) bad_layout(text, std::string("expected ") + what + " at character " +
                                         std::to_string(first + 1));
  return v;
}

void expect(std::string_view text, std::size_t& pos, char c, const char* where) {
  if (pos >= text.size() || text[pos] != c)
    bad_layout(text, std::string("expected '") + c + "' " + where + " at character " +
                         std::to_string(pos + 1));
  ++pos;
}

}  // namespace

MemoryLayout parse_memory_layout(std::string_view text) {
  MemoryLayout layout;
  std::size_t pos = 0;
  expect(text, pos, '@', "first");
  const std::size_t slash = text.find('/', pos);
  if (slash == std::string_view::npos) bad_layout(text, "no '/' after the name");
  layout.name = std::string(text.substr(pos, slash - pos));
  while (!layout.name.empty() && layout.name.back() == ' ') layout.name.pop_back();
  pos = slash;
  while (pos < text.size()) {
    expect(text, pos, '/', "before a start address");
    if (text.substr(pos, 2) != "0x" && text.substr(pos, 2) != "0X")
      bad_layout(text, "expected a start address 0x... at character " + std::to_string(pos + 1));
    pos += 2;
    std::uint64_t address = read_number(text, pos, true, "a start address");
    expect(text, pos, '/', "after the start address");
    for (;;) {
      MemorySegment s;
      s.start = static_cast<std::uint32_t>(address);
      s.pages = static_cast<std::uint32_t>(read_number(text, pos, false, "a page count"));
      expect(text, pos, '*', "after the page count");
      std::uint64_t size = read_number(text, pos, false, "a page size");
      if (pos >= text.size()) bad_layout(text, "the segment ends before its type letter");
      switch (text[pos]) {
        case 'B': case ' ': break;
        case 'K': size *= 1024; break;
        case 'M': size *= 1024 * 1024; break;
        default:
          bad_layout(text, std::string("unknown size multiplier '") + text[pos] +
                               "' (B, K, M) at character " + std::to_string(pos + 1));
      }
      ++pos;
      if (pos >= text.size() || text[pos] < 'a' || text[pos] > 'g')
        bad_layout(text, "expected a type letter a..g at character " + std::to_string(pos + 1));
      const int bits = text[pos] & 7;
      ++pos;
      s.readable = (bits & 1) != 0;
      s.erasable = (bits & 2) != 0;
      s.writable = (bits & 4) != 0;
      if (size == 0 || s.pages == 0) bad_layout(text, "a segment of zero bytes");
      s.page_size = static_cast<std::uint32_t>(size);
      if (s.end() > 0x100000000ull) bad_layout(text, "a segment past the 4 GB address space");
      layout.segments.push_back(s);
      address = s.end();
      if (pos < text.size() && text[pos] == ',') {
        ++pos;
        continue;
      }
      break;
    }
  }
  if (layout.segments.empty()) bad_layout(text, "no segments");
  return layout;
}

const MemorySegment* MemoryLayout::find(std::uint32_t address) const {
  for (const MemorySegment& s : segments)
    if (address >= s.start && address < s.end()) return &s;
  return nullptr;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> MemoryLayout::pages(
    std::uint32_t address, std::size_t size, bool need_erasable, bool need_writable) const {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  const std::uint64_t end = std::uint64_t{address} + size;
  const auto refuse = [&](std::uint64_t at, const std::string& why) {
    const std::string range =
        internal::hex32(address) + ".." + internal::hex32(static_cast<std::uint32_t>(end - 1));
    throw DfuseError(DfuseError::Kind::refused_address,
                     range + " (" + std::to_string(size) +
                         " bytes) refused before anything was sent: " +
                         internal::hex32(static_cast<std::uint32_t>(at)) + " " + why +
                         " in the device's memory layout \"" + name + "\"; check the image's "
                         "address and size",
                     static_cast<std::uint32_t>(at));
  };
  if (size == 0) return out;
  if (end > 0x100000000ull) refuse(address, "plus the size is past the 4 GB address space");
  std::uint64_t at = address;
  while (at < end) {
    const MemorySegment* s = find(static_cast<std::uint32_t>(at));
    if (s == nullptr) refuse(at, "is outside every segment");
    if (need_erasable && !s->erasable) refuse(at, "is in a segment that cannot be erased");
    if (need_writable && !s->writable) refuse(at, "is in a segment that cannot be written");
    const std::uint64_t page = s->start + (at - s->start) / s->page_size * s->page_size;
    out.emplace_back(static_cast<std::uint32_t>(page), s->page_size);
    at = page + s->page_size;
  }
  return out;
}

}  // namespace palp::dfu
