// SPDX-License-Identifier: Apache-2.0
#include "palp/protocol/cobs.hpp"

namespace palp::proto {

std::size_t cobs_encode(const u8* in, std::size_t n, u8* out, std::size_t capacity) {
  if (capacity < cobs_max_encoded(n)) return 0;
  // Each input byte becomes one output byte: a non-zero byte itself, a zero the code byte of the
  // block it opens (written when that block closes: the distance to the next zero or the end).
  // Only a block of 254 non-zero bytes breaks this: it closes with code 0xFF, consumes no zero
  // and adds a byte. So the input goes in chunks of kChunk bytes, each copied as it is with the
  // zeros' code bytes filled in behind, whenever the open block cannot reach 254 bytes within the
  // chunk; byte by byte, checking the length, otherwise (long zero-free runs, the tail). Sample
  // data is often half zeros, and a zero costs three instructions more than any other byte here
  // (firmware/core/README.md "Cost on the target").
  constexpr std::ptrdiff_t kChunk = 32;
  const u8* const end = in + n;
  u8* code = out;   // the open block's code byte
  u8* o = out + 1;  // the next output byte
  for (;;) {
    if (end - in >= kChunk && o - code < 0xFF - kChunk) {  // ends below 254 bytes
      for (std::ptrdiff_t i = 0; i < kChunk; ++i) {
        const u8 b = in[i];
        o[i] = b;  // a zero's slot is its block's code byte, overwritten when the block closes
        if (b == 0) {
          *code = static_cast<u8>(o + i - code);
          code = o + i;
        }
      }
      in += kChunk;
      o += kChunk;
      continue;
    }
    if (in == end) break;
    const u8 b = *in++;
    if (b == 0) {
      *code = static_cast<u8>(o - code);
      code = o++;
      continue;
    }
    *o++ = b;
    if (o - code == 0xFF) {  // 254 bytes: the block is full
      *code = 0xFF;
      if (in == end) return static_cast<std::size_t>(o - out);  // no code byte follows
      code = o++;
    }
  }
  *code = static_cast<u8>(o - code);
  return static_cast<std::size_t>(o - out);
}

int cobs_decode(const u8* in, std::size_t n, u8* out, std::size_t capacity) {
  std::size_t i = 0;
  std::size_t o = 0;
  while (i < n) {
    const u8 code = in[i++];
    if (code == 0) return -1;
    const std::size_t run = static_cast<std::size_t>(code) - 1;
    if (run > n - i) return -1;
    if (o + run > capacity) return -1;
    for (std::size_t k = 0; k < run; ++k) {
      if (in[i] == 0) return -1;
      out[o++] = in[i++];
    }
    // a block shorter than 254 data bytes implies a zero, except at the very end
    if (code != 0xFF && i < n) {
      if (o >= capacity) return -1;
      out[o++] = 0;
    }
  }
  return static_cast<int>(o);
}

}  // namespace palp::proto
