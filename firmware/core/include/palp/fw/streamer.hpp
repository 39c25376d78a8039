// SPDX-License-Identifier: Apache-2.0
// The stream, thread side (DESIGN.md "Streams"): samples taken by the control tick arrive here
// with their stream index; the streamer keeps them in the stream backlog, packs them into
// SampleBatch frames when the transmit buffer has room, and reports every loss where it happened:
//   - indices that never arrived were lost at the ISR queue (the tick could not hand them over);
//   - samples that arrived while the backlog was full are lost at the stream backlog (the host
//     did not drain);
// each loss becomes one EventStreamGap{first_missing_index, missing_count, stage} and sets
// StatusBit::after_gap on the next sample sent. Nothing is ever repeated or interpolated.
//
// Device time of sample k is exact: base_us + (start_tick - base_tick + k * decimation) /
// control_rate_Hz, where (base_tick, base_us) is the controller's time base: the tick and the
// device time of the last control-rate change (0, 0 before any), so device time runs on
// continuously across a rate change.
#pragma once

#include <cstddef>
#include <cstdint>

#include "palp/fw/ring.hpp"
#include "palp/protocol/messages.hpp"
#include "palp/protocol/stream.hpp"

namespace palp::fw {

/// Device time at a tick: the anchor of the current control rate (Controller::time_base()).
struct TimeBase {
  std::uint64_t tick = 0;  ///< the tick the current rate took effect at
  std::uint64_t us = 0;    ///< the device time then, µs
  /// Device time of `tick` at `rate_Hz` (tick >= this->tick).
  std::uint64_t us_of(std::uint64_t t, std::uint32_t rate_Hz) const {
    return us + (t - tick) * 1'000'000ull / rate_Hz;
  }
};

/// A sample as the control tick hands it over.
struct IndexedSample {
  std::uint32_t index = 0;
  proto::RawSample sample{};
};

/// Stream counters (part of Health).
struct StreamCounters {
  std::uint32_t isr_queue_overflows = 0;   ///< samples lost before reaching the streamer
  std::uint32_t stream_samples_lost = 0;   ///< samples lost because the backlog was full
  std::uint32_t stream_backlog_max = 0;    ///< deepest the backlog has been
  std::uint32_t stream_gaps = 0;           ///< EventStreamGap events emitted
};

class Streamer {
 public:
  static constexpr std::size_t kBacklogSamples = 1024;  ///< about 50 ms at 20 kHz
  /// The fastest stream the core produces: every control tick at the default 20 kHz (all 11
  /// channels in batches of 40: 499 500 bytes/s, 41 % of what USB full-speed bulk carries,
  /// firmware/usb/README.md "Throughput"); at a 40 kHz control rate every second tick (every
  /// tick there would be 999 000 bytes/s, 82 % of bulk's ceiling: no margin on a shared bus).
  static constexpr std::uint32_t kMaxRate_Hz = 20000;

  /// Validates and applies a configuration for a control rate; fills the reply. On refusal
  /// returns the error and the offending field index (Nak.field_index). A sample rate above
  /// max_rate_Hz (the board's limit, at most kMaxRate_Hz) is stream_too_fast.
  proto::ErrorCode configure(const proto::StreamConfigure& c, std::uint32_t control_rate_Hz,
                             proto::StreamConfig& reply, std::uint8_t& field_index,
                             std::uint32_t max_rate_Hz = kMaxRate_Hz);
  /// configure() in two steps: check() validates and computes the configuration touching no
  /// state (the controller runs it with the tick free: it has double arithmetic), apply() puts a
  /// configuration check() accepted for that control rate in force.
  static proto::ErrorCode check(const proto::StreamConfigure& c, std::uint32_t control_rate_Hz,
                                proto::StreamConfig& config, std::uint8_t& field_index,
                                std::uint32_t max_rate_Hz = kMaxRate_Hz);
  void apply(const proto::StreamConfig& config, std::uint32_t control_rate_Hz);
  const proto::StreamConfig& config() const { return config_; }

  /// Starts at control tick `tick` (device time from `base`): the next sample is index 0.
  void start(std::uint64_t tick, TimeBase base = {});
  void stop();
  bool running() const { return running_; }

  /// Tick side (call from the control tick): whether this tick takes a sample, and its index.
  /// Advances the decimation counter; call exactly once per tick while running.
  bool sample_due(std::uint32_t& index);
  /// Tick side: the index the next sample taken will have.
  std::uint32_t next_index() const { return next_index_; }

  /// Thread side: a sample arrives from the ISR queue.
  void accept(const IndexedSample& s);

  /// Thread side: packs what the backlog holds into frames. emit(const proto::Message&) must
  /// send the message or return false when the transmit buffer has no room (the streamer keeps
  /// it and tries again later). Gap events go first, in order. Sends only full batches unless
  /// flush is set (at stop).
  template <class Emit>
  void pump(Emit&& emit, bool flush = false);

  std::size_t backlog() const { return backlog_.size(); }
  const StreamCounters& counters() const { return counters_; }

 private:
  std::uint64_t time_us_of(std::uint32_t index) const;
  void note_gap(std::uint32_t first, std::uint32_t count, proto::GapStage stage);

  proto::StreamConfig config_{};
  std::uint32_t control_rate_Hz_ = 20000;
  bool running_ = false;
  std::uint64_t start_tick_ = 0;
  TimeBase base_{};
  std::uint32_t decimation_count_ = 0;
  std::uint32_t next_index_ = 0;   // tick side
  std::uint32_t expected_ = 0;     // thread side: the index that should arrive next
  bool after_gap_ = false;
  Ring<IndexedSample, kBacklogSamples> backlog_;
  Ring<proto::EventStreamGap, 16> gaps_;
  StreamCounters counters_{};
};

template <class Emit>
void Streamer::pump(Emit&& emit, bool flush) {
  while (!gaps_.empty()) {
    if (!emit(gaps_.at(0))) return;
    proto::EventStreamGap done;
    gaps_.pop(done);
    ++counters_.stream_gaps;
  }
  const std::size_t per_batch = config_.batch_samples;
  while (!backlog_.empty()) {
    // a batch is the run of consecutive indices at the front, at most batch_samples long; it is
    // sent when full, when a hole ends it (it cannot grow), or on flush
    const std::size_t avail = backlog_.size() < per_batch ? backlog_.size() : per_batch;
    // indices in the backlog only increase, so the run is whole when its last index says so (one
    // look instead of a walk every pass: firmware/core/README.md "Cost on the target")
    const std::uint32_t first = backlog_.at(0).index;
    std::size_t take = avail;
    if (backlog_.at(avail - 1).index != first + static_cast<std::uint32_t>(avail - 1)) {
      take = 1;
      while (take < avail && backlog_.at(take).index == first + take) ++take;
    }
    const bool hole_follows = take < avail;
    if (take < per_batch && !hole_follows && !flush) return;
    proto::SampleBatch b;
    b.first_index = backlog_.at(0).index;
    b.first_time_us = time_us_of(b.first_index);
    b.period_ns = config_.period_ns;
    b.channels = config_.channels;
    b.sample_count = static_cast<std::uint16_t>(take);
    // one bounds check for the batch; every channel is one copy a sample (proto::pack_sample_at)
    const std::size_t bytes = take * config_.bytes_per_sample;
    proto::Writer w(b.data.items.data(), b.data.items.size());
    proto::u8* p = w.claim(bytes);
    if (p == nullptr) return;  // cannot happen: configure() keeps batch_samples within the data
    for (std::size_t k = 0; k < take; ++k) p = proto::pack_sample_at(p, backlog_.at(k).sample, b.channels);
    b.data.size = static_cast<std::uint16_t>(bytes);
    if (!emit(static_cast<const proto::SampleBatch&>(b))) return;
    backlog_.drop_front(take);
  }
}

}  // namespace palp::fw
