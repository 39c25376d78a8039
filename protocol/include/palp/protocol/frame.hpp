// SPDX-License-Identifier: Apache-2.0
// Frames (SPEC.md §4): a header, a little-endian payload and a CRC-32, COBS-encoded and ended
// by one 0x00 byte. The same frames travel over USB bulk, HID reports, UART and TCP.
//
//   offset 0  u8   protocol major       offset 4  u16  sequence number
//   offset 1  u8   protocol minor       offset 6  u16  payload length (0..1024)
//   offset 2  u8   message id           offset 8  payload
//   offset 3  u8   flags                then      u32  CRC-32 of bytes [0, 8 + length)
#pragma once

#include <array>
#include <cstddef>

#include "palp/protocol/codec.hpp"
#include "palp/protocol/cobs.hpp"
#include "palp/protocol/crc32.hpp"
#include "palp/protocol/reject.hpp"

namespace palp::proto {

inline constexpr std::size_t kHeaderSize = 8;
inline constexpr std::size_t kCrcSize = 4;
inline constexpr std::size_t kMaxPayload = 1024;
inline constexpr std::size_t kMinFrame = kHeaderSize + kCrcSize;
inline constexpr std::size_t kMaxFrame = kHeaderSize + kMaxPayload + kCrcSize;
/// Largest encoded frame including its 0x00 delimiter: the buffer a sender needs.
inline constexpr std::size_t kMaxWireFrame = cobs_max_encoded(kMaxFrame) + 1;

/// Header flag bits. Undefined bits are sent as 0 and ignored on receipt.
enum FrameFlag : u8 {
  kFlagResponse = 0x01,  ///< answers the request with the same sequence number
};

struct FrameHeader {
  u8 major = kProtocolMajor;
  u8 minor = kProtocolMinor;
  u8 id = 0;
  u8 flags = 0;
  u16 seq = 0;
  u16 payload_len = 0;
  constexpr bool operator==(const FrameHeader&) const = default;
};

/// Encodes header (its payload_len is taken from size) and payload into out as wire bytes,
/// including the trailing 0x00. Returns the number of bytes, or 0 when out is too small or the
/// payload is larger than kMaxPayload.
std::size_t encode_frame(FrameHeader header, const u8* payload, std::size_t size, u8* out,
                         std::size_t capacity);

/// Completes a frame whose payload is already in raw[kHeaderSize, kHeaderSize + size): writes
/// the header (payload_len from size) and the CRC into raw, then the wire bytes into out.
/// raw must hold kMaxFrame bytes. Returns the number of wire bytes, 0 when out is too small.
std::size_t finish_frame(FrameHeader header, u8* raw, std::size_t size, u8* out,
                         std::size_t capacity);

/// Encodes message m as one wire frame. Returns the number of bytes written, 0 on overflow.
template <class M>
std::size_t encode_message(const M& m, u16 seq, u8 flags, u8* out, std::size_t capacity,
                           u8 major = kProtocolMajor, u8 minor = kProtocolMinor) {
  std::array<u8, kMaxFrame> raw;  // the payload is encoded in place, after the header
  const int n = encode_payload(m, raw.data() + kHeaderSize, kMaxPayload);
  if (n < 0) return 0;
  const FrameHeader h{major, minor, static_cast<u8>(M::kId), flags, seq, 0};
  return finish_frame(h, raw.data(), static_cast<std::size_t>(n), out, capacity);
}

/// A frame that passed every frame-level check; payload points into the reader's buffer and is
/// valid until the next call to feed().
struct Frame {
  FrameHeader header;
  const u8* payload;
};

/// Checks one decoded (un-COBSed) frame: length, CRC, payload length, major version.
Reject parse_frame(const u8* data, std::size_t size, Frame& out);

/// Incremental frame reader: feed it bytes as they arrive, in chunks of any size. Runs of 0x00
/// are idle; any other bytes up to a 0x00 are one frame, checked and accepted or rejected, so
/// garbage costs one rejected frame and the reader is in step again at the next 0x00. It never allocates and never holds more than one frame. Every frame it completes is
/// counted exactly once in counters(): under Reject::ok when accepted, else under its reason.
class FrameReader {
 public:
  /// Frame level only: calls on_frame(const Frame&) for each frame that passes the frame checks
  /// and on_reject(Reject) for each that does not.
  template <class OnFrame, class OnReject>
  void feed(const u8* data, std::size_t size, OnFrame&& on_frame, OnReject&& on_reject) {
    feed_frames(
        data, size,
        [&](const Frame& f) {
          counters_.count(Reject::ok);
          on_frame(f);
        },
        on_reject);
  }

  /// Frames and messages: decodes each accepted frame's payload and calls
  /// on_message(const FrameHeader&, const M&) with the typed message, or on_reject with the
  /// frame-level or message-level reason (unknown_message, short_payload, bad_field). on_reject
  /// takes (Reject) or (Reject, const FrameHeader*); the header is given for message-level
  /// rejects (so a device can answer with Nak) and is nullptr for frame-level ones.
  template <class OnMessage, class OnReject>
  void feed_messages(const u8* data, std::size_t size, OnMessage&& on_message,
                     OnReject&& on_reject) {
    auto reject = [&](Reject r, const FrameHeader* h) {
      if constexpr (std::is_invocable_v<OnReject&, Reject, const FrameHeader*>) on_reject(r, h);
      else on_reject(r);
    };
    feed_frames(
        data, size,
        [&](const Frame& f) {
          const Reject r = decode_message(f.header.id, f.payload, f.header.payload_len,
                                          [&](const auto& m) { on_message(f.header, m); });
          counters_.count(r);
          if (r != Reject::ok) reject(r, &f.header);
        },
        [&](Reject r) { reject(r, nullptr); });
  }

  const RejectCounters& counters() const { return counters_; }
  /// Bytes held toward the next frame (for tests and health).
  std::size_t pending() const { return len_; }

 private:
  template <class OnFrame, class OnReject>
  void feed_frames(const u8* data, std::size_t size, OnFrame&& on_frame, OnReject&& on_reject) {
    for (std::size_t k = 0; k < size; ++k) {
      const u8 b = data[k];
      if (b != 0) {
        if (len_ < buf_.size()) buf_[len_++] = b;
        else overflow_ = true;
        continue;
      }
      if (overflow_) {
        counters_.count(Reject::oversize);
        on_reject(Reject::oversize);
      } else if (len_ > 0) {
        Frame f{};
        const Reject r = finish(f);
        if (r == Reject::ok) {
          on_frame(static_cast<const Frame&>(f));
        } else {
          counters_.count(r);
          on_reject(r);
        }
      }
      len_ = 0;
      overflow_ = false;
    }
  }
  Reject finish(Frame& out);

  std::array<u8, cobs_max_encoded(kMaxFrame)> buf_{};
  std::size_t len_ = 0;
  bool overflow_ = false;
  RejectCounters counters_{};
};

}  // namespace palp::proto
