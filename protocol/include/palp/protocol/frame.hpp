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

/// Encodes message m as one wire frame. Returns the number of bytes written, 0 on overflow.
template <class M>
std::size_t encode_message(const M& m, u16 seq, u8 flags, u8* out, std::size_t capacity,
                           u8 major = kProtocolMajor, u8 minor = kProtocolMinor) {
  std::array<u8, kMaxPayload> payload;
  const int n = encode_payload(m, payload.data(), payload.size());
  if (n < 0) return 0;
  FrameHeader h{major, minor, static_cast<u8>(M::kId), flags, seq, 0};
  return encode_frame(h, payload.data(), static_cast<std::size_t>(n), out, capacity);
}

/// A frame that passed every frame-level check; payload points into the reader's buffer and is
/// valid until the next call to feed().
struct Frame {
  FrameHeader header;
  const u8* payload;
};

/// Checks one decoded (un-COBSed) frame: length, CRC, payload length, major version.
Reject parse_frame(const u8* data, std::size_t size, Frame& out);

/// Incremental frame reader: feed it bytes as they arrive, in chunks of any size. It calls
/// on_frame(const Frame&) for each valid frame and on_reject(Reject) for each rejected one, and
/// counts both. Bytes before the first delimiter and runs of 0x00 are skipped; after garbage it
/// resynchronises at the next 0x00. It never allocates and never holds more than one frame.
class FrameReader {
 public:
  template <class OnFrame, class OnReject>
  void feed(const u8* data, std::size_t size, OnFrame&& on_frame, OnReject&& on_reject) {
    for (std::size_t k = 0; k < size; ++k) {
      const u8 b = data[k];
      if (b != 0) {
        if (len_ < buf_.size()) buf_[len_++] = b;
        else overflow_ = true;
        continue;
      }
      if (overflow_) {
        reject(Reject::oversize, on_reject);
      } else if (len_ > 0) {
        Frame f{};
        const Reject r = finish(f);
        if (r == Reject::ok) {
          counters_.count(Reject::ok);
          on_frame(static_cast<const Frame&>(f));
        } else {
          reject(r, on_reject);
        }
      }
      len_ = 0;
      overflow_ = false;
    }
  }

  /// Counts a rejection found after the frame level (unknown message, short payload, bad field),
  /// so that one set of counters covers the whole receive path.
  void count_message_reject(Reject r) {
    counters_.count(r);
    // the frame was counted as accepted at frame level; move it to its real reason
    if (counters_.by_reason[0] > 0) --counters_.by_reason[0];
  }

  const RejectCounters& counters() const { return counters_; }
  /// Bytes held toward the next frame (for tests and health).
  std::size_t pending() const { return len_; }

 private:
  template <class OnReject>
  void reject(Reject r, OnReject& on_reject) {
    counters_.count(r);
    on_reject(r);
  }
  Reject finish(Frame& out);

  std::array<u8, cobs_max_encoded(kMaxFrame)> buf_{};
  std::size_t len_ = 0;
  bool overflow_ = false;
  RejectCounters counters_{};
};

}  // namespace palp::proto
