#include "palp/protocol/cobs.hpp"

namespace palp::proto {

std::size_t cobs_encode(const u8* in, std::size_t n, u8* out, std::size_t capacity) {
  if (capacity < cobs_max_encoded(n)) return 0;
  // One pass, a byte a step: a non-zero byte is copied; a zero closes the block (its code byte,
  // the block's length + 1, is written back) and opens the next; a block of 254 copied bytes
  // closes with code 0xFF and consumes no zero. A zero costs about what any other byte costs:
  // sample data is often half zeros (firmware/core/README.md "Cost on the target").
  const u8* const end = in + n;
  u8* code = out;
  u8* o = out + 1;
  std::size_t room = 254;  // bytes the open block can still take
  while (in != end) {
    const u8 b = *in++;
    if (b != 0) {
      *o++ = b;
      if (--room != 0) continue;
      *code = 0xFF;
      if (in == end) return static_cast<std::size_t>(o - out);  // no code byte follows
    } else {
      *code = static_cast<u8>(255 - room);
    }
    code = o++;
    room = 254;
  }
  *code = static_cast<u8>(255 - room);
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
