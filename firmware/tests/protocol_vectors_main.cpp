// SPDX-License-Identifier: Apache-2.0
// The protocol's golden vectors, checked on the target (Cortex-M4F, under QEMU mps2-an386):
// the same palp_protocol library the firmware links, built by the cross compiler, must read and
// write exactly the bytes the host SDK does.
//
// messages.txt, for every vector: feeding the wire bytes through a FrameReader accepts exactly
// one frame and rejects nothing; the frame's header equals the vector's header; its payload
// equals the vector's payload; decode_message() decodes it; encode_message() with the frame's
// seq, flags, major and minor gives back exactly the wire bytes.
// malformed.txt, for every vector: what a receiver makes of the bytes (FrameReader, then
// decode_message; the same as receive_outcomes() in protocol/host/vectors.cpp) equals `expect`,
// fed in one piece and fed byte by byte as a UART delivers them.
//
// Output on the console (UART0): one `FAIL file:line name: ...` line per failing vector, the
// stack high-water mark, and the summary line
//   protocol vectors on cortex-m4: <n> messages, <n> malformed, <n> failures
// Exit code (semihosting): 0 when every vector passes, 1 otherwise.
#include <array>
#include <cstddef>
#include <cstdint>

#include "board.hpp"
#include "console.hpp"
#include "palp/protocol/codec.hpp"
#include "palp/protocol/frame.hpp"
#include "palp_golden_vectors.hpp"

namespace {

using namespace palp::proto;
using palp::fw::Console;
using palp::fw::dec;
using palp::fw::hex;
using palp::fw::vectors::MalformedVector;
using palp::fw::vectors::MessageVector;

Console console;
u32 failures = 0;

// An initialised variable lives in .data, which QEMU loads only at its load address in flash:
// it reads right only if startup copied .data to RAM.
constexpr u32 kDataWord = 0x600DDA7Au;
volatile u32 data_word = kDataWord;

// Starts a failure line; the caller appends the details and '\n'.
Console& fail(const char* file, u32 line, const char* name) {
  ++failures;
  return console << "FAIL " << file << ':' << dec(line) << ' ' << name << ": ";
}

// Index of the first difference of a[0, na) and b[0, nb), or -1 when they are equal.
long first_difference(const u8* a, std::size_t na, const u8* b, std::size_t nb) {
  const std::size_t n = na < nb ? na : nb;
  for (std::size_t k = 0; k < n; ++k)
    if (a[k] != b[k]) return static_cast<long>(k);
  return na == nb ? -1 : static_cast<long>(n);
}

Console& operator<<(Console& c, const FrameHeader& h) {
  return c << "major=" << dec(h.major) << " minor=" << dec(h.minor) << " id=0x" << hex(h.id, 2)
           << " flags=0x" << hex(h.flags, 2) << " seq=" << dec(h.seq)
           << " payload_len=" << dec(h.payload_len);
}

// Re-encoded frames go here (static: the stack already holds a FrameReader and a message).
std::array<u8, kMaxWireFrame> reencoded;

void check_message(const MessageVector& v) {
  const char* file = "messages.txt";
  FrameReader reader;
  u32 frames = 0;
  u32 rejects = 0;
  Reject first_reject = Reject::ok;
  Frame frame{};
  reader.feed(
      v.wire, v.wire_size,
      [&](const Frame& f) {
        if (frames++ == 0) frame = f;
      },
      [&](Reject r) {
        if (rejects++ == 0) first_reject = r;
      });
  if (rejects != 0) {
    fail(file, v.line, v.name) << "FrameReader rejected it: " << reject_name(first_reject)
                               << '\n';
    return;
  }
  if (frames != 1) {
    fail(file, v.line, v.name) << "FrameReader accepted " << dec(frames) << " frames, want 1\n";
    return;
  }
  // frame.payload points into the reader's buffer: valid until the next feed().
  const FrameHeader& h = frame.header;
  const FrameHeader want{v.major, v.minor, v.id, v.flags, v.seq, v.payload_len};
  if (!(h == want)) {
    fail(file, v.line, v.name) << "header " << h << ", want " << want << '\n';
    return;
  }
  if (const long at = first_difference(frame.payload, h.payload_len, v.payload, v.payload_size);
      at >= 0) {
    fail(file, v.line, v.name) << "payload (" << dec(h.payload_len) << " bytes) differs from the "
                               << "vector's payload (" << dec(static_cast<u32>(v.payload_size))
                               << " bytes) at byte " << dec(static_cast<u32>(at)) << '\n';
    return;
  }
  std::size_t n = 0;
  bool decoded = false;
  const Reject r = decode_message(h.id, frame.payload, h.payload_len, [&](const auto& m) {
    decoded = true;
    n = encode_message(m, h.seq, h.flags, reencoded.data(), reencoded.size(), h.major, h.minor);
  });
  if (r != Reject::ok || !decoded) {
    fail(file, v.line, v.name) << "decode_message: " << reject_name(r) << '\n';
    return;
  }
  if (n == 0) {
    fail(file, v.line, v.name) << "encode_message returned 0 (overflow)\n";
    return;
  }
  if (const long at = first_difference(reencoded.data(), n, v.wire, v.wire_size); at >= 0) {
    const auto k = static_cast<std::size_t>(at);
    fail(file, v.line, v.name) << "re-encoded " << dec(static_cast<u32>(n))
                               << " bytes differ from the " << dec(static_cast<u32>(v.wire_size))
                               << " wire bytes at byte " << dec(static_cast<u32>(k));
    if (k < n && k < v.wire_size)
      console << " (0x" << hex(reencoded[k], 2) << ", want 0x" << hex(v.wire[k], 2) << ')';
    console << '\n';
  }
}

// What a receiver makes of a byte stream, in order: reject names and accepted message names.
struct Outcomes {
  std::array<const char*, 16> items{};
  std::size_t size = 0;
  bool overflow = false;
  void add(const char* s) {
    if (size < items.size()) items[size++] = s;
    else overflow = true;
  }
};

Outcomes receive(const u8* wire, std::size_t size, std::size_t chunk) {
  Outcomes out;
  FrameReader reader;
  auto on_message = [&](const FrameHeader&, const auto& m) { out.add(m.kName); };
  auto on_reject = [&](Reject r) { out.add(reject_name(r)); };
  for (std::size_t k = 0; k < size; k += chunk)
    reader.feed_messages(wire + k, size - k < chunk ? size - k : chunk, on_message, on_reject);
  return out;
}

// Does `expect` ("bad_cobs Ping", or "-" for nothing) list exactly these outcomes?
bool matches(const Outcomes& got, const char* expect) {
  if (got.overflow) return false;
  if (expect[0] == '-' && expect[1] == '\0') return got.size == 0;
  std::size_t k = 0;
  const char* p = expect;
  while (*p != '\0') {
    while (*p == ' ') ++p;
    if (*p == '\0') break;
    if (k == got.size) return false;
    const char* s = got.items[k++];
    while (*p != '\0' && *p != ' ' && *s != '\0' && *p == *s) ++p, ++s;
    if (*s != '\0' || (*p != '\0' && *p != ' ')) return false;
  }
  return k == got.size;
}

Console& operator<<(Console& c, const Outcomes& o) {
  if (o.size == 0) c << '-';
  for (std::size_t k = 0; k < o.size; ++k) c << (k == 0 ? "" : " ") << o.items[k];
  if (o.overflow) c << " ...";
  return c;
}

void check_malformed(const MalformedVector& v) {
  const char* file = "malformed.txt";
  const Outcomes whole = receive(v.wire, v.wire_size, v.wire_size);
  if (!matches(whole, v.expect)) {
    fail(file, v.line, v.name) << "got " << whole << ", want " << v.expect << " (" << v.about
                               << ")\n";
    return;
  }
  const Outcomes bytewise = receive(v.wire, v.wire_size, 1);
  if (!matches(bytewise, v.expect)) {
    fail(file, v.line, v.name) << "fed byte by byte: got " << bytewise << ", want " << v.expect
                               << " (" << v.about << ")\n";
  }
}

}  // namespace

int main() {
  namespace gv = palp::fw::vectors;
  console << "palp protocol " << dec(kProtocolMajor) << '.' << dec(kProtocolMinor)
          << " golden vectors on the target\n"
          << "vectors messages.txt sha256 " << gv::kMessagesSha256 << '\n'
          << "vectors malformed.txt sha256 " << gv::kMalformedSha256 << '\n';

  if (data_word != kDataWord) {
    ++failures;
    console << "FAIL startup: a .data variable reads 0x" << hex(data_word, 8) << ", want 0x"
            << hex(kDataWord, 8) << " (.data not copied from flash)\n";
  }
  for (const MessageVector& v : gv::kMessages) check_message(v);
  for (const MalformedVector& v : gv::kMalformed) check_malformed(v);

  console << "stack used: " << dec(static_cast<u32>(palp::board::stack_used())) << " of "
          << dec(static_cast<u32>(palp::board::stack_size())) << " bytes\n";
  console << "protocol vectors on cortex-m4: " << dec(static_cast<u32>(gv::kMessageCount))
          << " messages, " << dec(static_cast<u32>(gv::kMalformedCount)) << " malformed, "
          << dec(failures) << " failures\n";
  return failures == 0 ? 0 : 1;
}
