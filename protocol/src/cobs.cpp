#include "palp/protocol/cobs.hpp"

namespace palp::proto {

std::size_t cobs_encode(const u8* in, std::size_t n, u8* out, std::size_t capacity) {
  if (capacity < cobs_max_encoded(n)) return 0;
  std::size_t code_pos = 0;  // where the current block's code byte goes
  std::size_t o = 1;
  u8 code = 1;
  for (std::size_t k = 0; k < n; ++k) {
    if (in[k] == 0) {
      out[code_pos] = code;
      code_pos = o++;
      code = 1;
      continue;
    }
    out[o++] = in[k];
    if (++code == 0xFF) {
      out[code_pos] = code;
      if (k + 1 == n) return o;  // a full block ends the input: no code byte follows
      code_pos = o++;
      code = 1;
    }
  }
  out[code_pos] = code;
  return o;
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
