// SPDX-License-Identifier: Apache-2.0
#include "palp/protocol/frame.hpp"

namespace palp::proto {

namespace {
constexpr u16 load_u16(const u8* p) { return static_cast<u16>(p[0] | (p[1] << 8)); }
constexpr u32 load_u32(const u8* p) {
  return static_cast<u32>(p[0]) | (static_cast<u32>(p[1]) << 8) | (static_cast<u32>(p[2]) << 16) |
         (static_cast<u32>(p[3]) << 24);
}
}  // namespace

std::size_t encode_frame(FrameHeader h, const u8* payload, std::size_t size, u8* out,
                         std::size_t capacity) {
  if (size > kMaxPayload) return 0;
  std::array<u8, kMaxFrame> raw;
  for (std::size_t k = 0; k < size; ++k) raw[kHeaderSize + k] = payload[k];
  return finish_frame(h, raw.data(), size, out, capacity);
}

std::size_t finish_frame(FrameHeader h, u8* raw, std::size_t size, u8* out,
                         std::size_t capacity) {
  if (size > kMaxPayload) return 0;
  h.payload_len = static_cast<u16>(size);
  raw[0] = h.major;
  raw[1] = h.minor;
  raw[2] = h.id;
  raw[3] = h.flags;
  raw[4] = static_cast<u8>(h.seq);
  raw[5] = static_cast<u8>(h.seq >> 8);
  raw[6] = static_cast<u8>(h.payload_len);
  raw[7] = static_cast<u8>(h.payload_len >> 8);
  const std::size_t body = kHeaderSize + size;
  const u32 crc = crc32(raw, body);
  for (std::size_t k = 0; k < 4; ++k) raw[body + k] = static_cast<u8>(crc >> (8 * k));
  const std::size_t n = cobs_encode(raw, body + kCrcSize, out, capacity);
  if (n == 0 || n >= capacity) return 0;
  out[n] = 0;
  return n + 1;
}

Reject parse_frame(const u8* data, std::size_t size, Frame& out) {
  if (size < kMinFrame) return Reject::truncated;
  const std::size_t body = size - kCrcSize;
  if (crc32(data, body) != load_u32(data + body)) return Reject::bad_crc;
  FrameHeader h{data[0], data[1], data[2], data[3], load_u16(data + 4), load_u16(data + 6)};
  if (h.payload_len > kMaxPayload) return Reject::oversize;
  if (kHeaderSize + h.payload_len != body) return Reject::length_mismatch;
  if (h.major != kProtocolMajor && !is_frozen_id(h.id)) return Reject::unsupported_major;
  out.header = h;
  out.payload = data + kHeaderSize;
  return Reject::ok;
}

Reject FrameReader::finish(Frame& out) {
  const int n = cobs_decode(buf_.data(), len_, buf_.data(), buf_.size());
  if (n < 0) return Reject::bad_cobs;
  return parse_frame(buf_.data(), static_cast<std::size_t>(n), out);
}

}  // namespace palp::proto
