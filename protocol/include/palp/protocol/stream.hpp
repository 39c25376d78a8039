// SPDX-License-Identifier: Apache-2.0
// Stream samples (SPEC.md §9): the channels of a sample, their scaling, and the byte rate of a
// stream configuration. A SampleBatch's data holds sample_count samples back to back; each
// sample holds the channels whose bits are set, in bit order, little-endian, no padding.
#pragma once

#include <bit>
#include <cstddef>
#include <cstring>

#include "palp/protocol/cobs.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/messages.hpp"

namespace palp::proto {

inline constexpr double kCurrentLsb_A = 0.0002;   ///< i_cmd, i_meas: i16
inline constexpr double kPressureLsb_Pa = 0.05;   ///< p1..p6: i16
inline constexpr double kVoltageLsb_V = 0.001;    ///< v_cmd: i16
inline constexpr u16 kAllChannels = 0x07FF;
inline constexpr std::size_t kMaxBatchData = 960;  ///< SampleBatch.data capacity

/// One sample as it is on the wire: scaled integers. Absent channels are left zero.
struct RawSample {
  i16 i_cmd = 0;
  i16 i_meas = 0;
  i32 encoder = 0;
  Arr<i16, 6> pressure{};
  u16 status = 0;
  i16 v_cmd = 0;
  constexpr bool operator==(const RawSample&) const = default;
};

/// Size in bytes of one sample carrying the channels in mask (bits above Channel::v_cmd ignored).
constexpr std::size_t bytes_per_sample(u16 mask) {
  // two bytes a channel, four for the encoder (the known channels are bits 0..v_cmd: kAllChannels)
  static_assert(kAllChannels == (2u << static_cast<u8>(Channel::v_cmd)) - 1u);
  const unsigned known = mask & kAllChannels;
  return 2u * static_cast<std::size_t>(std::popcount(known)) +
         ((known >> static_cast<u8>(Channel::encoder)) & 1u) * 2u;
}

/// What is wrong with a SampleBatch, if anything (a receiver checks every batch before use).
enum class BatchProblem : u8 {
  none,
  unknown_channels,  ///< channel bits this build does not know: the device must never send them
  size_mismatch,     ///< data is not sample_count x bytes_per_sample(channels) bytes
  zero_period,       ///< period_ns is 0
};
constexpr const char* batch_problem_name(BatchProblem p) {
  switch (p) {
    case BatchProblem::none: return "none";
    case BatchProblem::unknown_channels: return "unknown_channels";
    case BatchProblem::size_mismatch: return "size_mismatch";
    case BatchProblem::zero_period: return "zero_period";
  }
  return "invalid";
}
constexpr BatchProblem check_batch(const SampleBatch& b) {
  if ((b.channels & ~kAllChannels) != 0) return BatchProblem::unknown_channels;
  if (b.data.size != static_cast<std::size_t>(b.sample_count) * bytes_per_sample(b.channels))
    return BatchProblem::size_mismatch;
  if (b.period_ns == 0) return BatchProblem::zero_period;
  return BatchProblem::none;
}

namespace detail {
// With every channel, the wire sample is RawSample's own bytes on a little-endian machine (the
// fields in bit order, no padding): one copy instead of eleven stores.
inline constexpr bool kRawSampleIsWireSample =
    std::endian::native == std::endian::little && sizeof(RawSample) == 24 &&
    offsetof(RawSample, i_cmd) == 0 && offsetof(RawSample, i_meas) == 2 &&
    offsetof(RawSample, encoder) == 4 && offsetof(RawSample, pressure) == 8 &&
    offsetof(RawSample, status) == 20 && offsetof(RawSample, v_cmd) == 22;
static_assert(sizeof(RawSample) != 24 || bytes_per_sample(kAllChannels) == sizeof(RawSample));
/// A store per channel present (any mask, any byte order).
u8* pack_channels(u8* p, const RawSample& s, u16 mask);
}  // namespace detail

/// Appends one sample's selected channels to w.
void pack_sample(Writer& w, const RawSample& s, u16 mask);
/// The same without a Writer: writes bytes_per_sample(mask) bytes at p (the caller checked the
/// room, e.g. with Writer::claim once for a run of samples) and returns the end. Every channel
/// on a little-endian machine is one copy (inline); other masks a store per channel.
inline u8* pack_sample_at(u8* p, const RawSample& s, u16 mask) {
  if (detail::kRawSampleIsWireSample && (mask & kAllChannels) == kAllChannels) {
    std::memcpy(p, &s, sizeof s);
    return p + sizeof s;
  }
  return detail::pack_channels(p, s, mask);
}
/// Reads one sample's selected channels from r; false when r runs out.
bool unpack_sample(Reader& r, RawSample& s, u16 mask);

/// The most samples of this channel mask that fit one SampleBatch.
constexpr std::size_t max_batch_samples(u16 mask) {
  const std::size_t b = bytes_per_sample(mask);
  return b == 0 ? 0 : kMaxBatchData / b;
}

/// Bytes on the wire for one SampleBatch frame of n samples: header, payload, CRC, the worst-case
/// COBS overhead and the delimiter.
constexpr std::size_t batch_wire_bytes(u16 mask, std::size_t n) {
  const std::size_t payload = 4 + 8 + 4 + 2 + 2 + 2 + n * bytes_per_sample(mask);
  const std::size_t frame = kHeaderSize + payload + kCrcSize;
  return cobs_max_encoded(frame) + 1;
}

/// Wire bytes per second of a stream of rate_Hz samples per second in batches of n (rounded up).
constexpr u32 stream_wire_bytes_per_s(u16 mask, double rate_Hz, std::size_t n) {
  if (n == 0) return 0;
  const double v = rate_Hz / static_cast<double>(n) * static_cast<double>(batch_wire_bytes(mask, n));
  const u32 whole = static_cast<u32>(v);
  return static_cast<double>(whole) < v ? whole + 1 : whole;
}

}  // namespace palp::proto
