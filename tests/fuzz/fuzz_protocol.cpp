// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for everything that reads protocol bytes from outside: the frame reader
// (COBS, CRC, header checks) and every message decoder. Properties checked on every input:
//  - nothing crashes, reads out of bounds or allocates (ASan/UBSan watch);
//  - every frame-level callback is counted exactly once, under its reason;
//  - an accepted message re-encodes to a payload that decodes to the same bytes again, and its
//    re-encoded frame is accepted by a fresh reader with the same header;
//  - the first byte taken as a message id and the rest as its payload decodes or is rejected
//    with a reason (the decoders fuzzed directly, without a valid CRC in the way).
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "palp/protocol/frame.hpp"

namespace {

using namespace palp::proto;

[[noreturn]] void fail() { __builtin_trap(); }

template <class M>
void check_round_trip(const M& m) {
  static u8 first[kMaxPayload];
  static u8 second[kMaxPayload];
  const int n = encode_payload(m, first, sizeof first);
  if (n < 0) fail();
  M again;
  if (decode_payload(first, static_cast<std::size_t>(n), again) != Reject::ok) fail();
  const int n2 = encode_payload(again, second, sizeof second);
  if (n2 != n) fail();
  for (int k = 0; k < n; ++k)
    if (first[k] != second[k]) fail();

  static u8 wire[kMaxWireFrame];
  const std::size_t w = encode_message(m, 0x1234, kFlagResponse, wire, sizeof wire);
  if (w == 0) fail();
  FrameReader reader;
  int frames = 0;
  reader.feed(
      wire, w,
      [&](const Frame& f) {
        ++frames;
        if (f.header.id != static_cast<u8>(M::kId) || f.header.seq != 0x1234 ||
            f.header.payload_len != n)
          fail();
      },
      [&](Reject) { fail(); });
  if (frames != 1) fail();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FrameReader reader;
  u32 callbacks = 0;
  reader.feed_messages(
      data, size,
      [&](const FrameHeader&, const auto& m) {
        ++callbacks;
        check_round_trip(m);
      },
      [&](Reject r) {
        ++callbacks;
        if (r == Reject::ok) fail();
      });
  u32 counted = 0;
  for (u32 c : reader.counters().by_reason) counted += c;
  if (counted != callbacks) fail();
  if (reader.pending() > cobs_max_encoded(kMaxFrame)) fail();

  if (size > 0) {
    const Reject r = decode_message(data[0], data + 1, size - 1,
                                    [](const auto& m) { check_round_trip(m); });
    if (r == Reject::bad_cobs || r == Reject::bad_crc) fail();  // not decoder reasons
  }
  return 0;
}
