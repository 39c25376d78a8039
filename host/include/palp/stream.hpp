// SPDX-License-Identifier: Apache-2.0
// Streaming: samples in order, with their index and device time, and every loss as an explicit
// gap record. Nothing is ever filled in or repeated.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <variant>

namespace palp {

/// Channel bits of a stream (protocol Channel enum): which values each sample carries.
namespace channel {
inline constexpr std::uint16_t i_cmd = 1u << 0;
inline constexpr std::uint16_t i_meas = 1u << 1;
inline constexpr std::uint16_t encoder = 1u << 2;
inline constexpr std::uint16_t pressure = 0x3Fu << 3;  ///< p1..p6
inline constexpr std::uint16_t status = 1u << 9;
inline constexpr std::uint16_t v_cmd = 1u << 10;
inline constexpr std::uint16_t all = 0x07FF;
}  // namespace channel

/// What to stream. The rate must divide the device's control rate (20 kHz: 10 kHz, 5 kHz,
/// 2 kHz, 1 kHz, ...); batch_samples 0 picks about 25 batches per second.
struct StreamSettings {
  double rate_Hz = 1000.0;
  std::uint16_t channels = channel::all;
  std::uint16_t batch_samples = 0;
};

/// The stream configuration in force, as the device confirmed it.
struct StreamInfo {
  double rate_Hz = 0;
  double period_s = 0;
  std::uint16_t channels = 0;
  std::uint16_t batch_samples = 0;
  std::uint32_t wire_bytes_per_s = 0;  ///< what it costs on the transport
};

/// One sample, SI units. Channels that are not streamed are 0 (see StreamInfo::channels).
struct Sample {
  std::uint64_t index = 0;    ///< from 0 at the stream's start, never wraps (the wire's 32-bit
                              ///< index is extended by the SDK)
  double t_device_s = 0;      ///< device clock (exact: the device's µs time of the sample)
  double t_host_s = 0;        ///< the same instant on the host's steady clock (estimated)
  double i_cmd_A = 0;         ///< commanded coil current
  double i_A = 0;             ///< measured coil current
  double z_m = 0;             ///< encoder position, +z into the specimen, device's zero
  std::int32_t encoder_counts = 0;  ///< the same position in counts (1 count = 1 µm)
  std::array<double, 6> p_Pa{};     ///< pressure channels 1..6
  std::uint16_t status = 0;   ///< StatusBit bits
  double v_cmd_V = 0;         ///< commanded coil voltage
};

/// Where samples were lost.
enum class GapSource : std::uint8_t {
  isr_queue,       ///< device: the control ISR's sample queue was full
  stream_backlog,  ///< device: the stream backlog was full
  usb_in,          ///< device: the host did not drain the USB IN endpoint
  transport,       ///< between device and host: frames lost or rejected (seen in the indices)
  host_queue,      ///< host: the SDK's queue was full (the application did not consume)
  reconnect,       ///< the link was lost and restored; the stream restarted
};
const char* gap_source_name(GapSource s);

/// Samples [first_index, first_index + count) are missing. For reconnect gaps the count is the
/// samples the stream would have produced while the link was down, estimated from device time.
struct Gap {
  std::uint64_t first_index = 0;
  std::uint64_t count = 0;
  GapSource source = GapSource::transport;
  double t_device_s = 0;  ///< device time of the first missing sample
  /// False only for a reconnect after which the device's clock restarted (a reset device or a
  /// restarted simulator): then nobody knows how many samples were missed, and count is 0.
  bool count_known = true;
};

using StreamItem = std::variant<Sample, Gap>;

/// Device time to host time: host = offset + (1 + drift) * device, fitted over recent Ping
/// round trips (the lowest-latency ones weigh most) and re-estimated as they come.
struct ClockMapping {
  double offset_s = 0;
  double drift = 0;      ///< relative rate difference (host s per device s, minus 1)
  double rtt_s = 0;      ///< the best round trip in the fit window
  std::size_t points = 0;
  double to_host_s(double device_s) const { return offset_s + (1.0 + drift) * device_s; }
};

}  // namespace palp
