// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/streamer.hpp"

namespace palp::fw {

proto::ErrorCode Streamer::configure(const proto::StreamConfigure& c,
                                     std::uint32_t control_rate_Hz, proto::StreamConfig& reply,
                                     std::uint8_t& field_index, std::uint32_t max_rate_Hz) {
  const proto::ErrorCode e = check(c, control_rate_Hz, reply, field_index, max_rate_Hz);
  if (e == proto::ErrorCode::ok) apply(reply, control_rate_Hz);
  return e;
}

proto::ErrorCode Streamer::check(const proto::StreamConfigure& c, std::uint32_t control_rate_Hz,
                                 proto::StreamConfig& config, std::uint8_t& field_index,
                                 std::uint32_t max_rate_Hz) {
  const int bad = c.first_out_of_range();
  if (bad >= 0) {
    field_index = static_cast<std::uint8_t>(bad);
    return proto::ErrorCode::out_of_range;
  }
  if (c.batch_samples > proto::max_batch_samples(c.channels)) {
    field_index = proto::field_index_of<&proto::StreamConfigure::batch_samples>();
    return proto::ErrorCode::out_of_range;
  }
  if (max_rate_Hz > kMaxRate_Hz) max_rate_Hz = kMaxRate_Hz;
  if (static_cast<std::uint64_t>(control_rate_Hz) > std::uint64_t{max_rate_Hz} * c.decimation) {
    field_index = proto::field_index_of<&proto::StreamConfigure::decimation>();
    return proto::ErrorCode::stream_too_fast;
  }
  config.channels = c.channels;
  config.decimation = c.decimation;
  config.batch_samples = c.batch_samples;
  config.period_ns = static_cast<std::uint32_t>(
      static_cast<std::uint64_t>(c.decimation) * 1'000'000'000ull / control_rate_Hz);
  config.bytes_per_sample = static_cast<std::uint16_t>(proto::bytes_per_sample(c.channels));
  config.wire_bytes_per_s = proto::stream_wire_bytes_per_s(
      c.channels, static_cast<double>(control_rate_Hz) / c.decimation, c.batch_samples);
  return proto::ErrorCode::ok;
}

void Streamer::apply(const proto::StreamConfig& config, std::uint32_t control_rate_Hz) {
  control_rate_Hz_ = control_rate_Hz;
  config_ = config;
}

void Streamer::start(std::uint64_t tick, TimeBase base) {
  running_ = true;
  start_tick_ = tick;
  base_ = base;
  decimation_count_ = 0;
  next_index_ = 0;
  expected_ = 0;
  after_gap_ = false;
  backlog_.clear();
  gaps_.clear();
}

void Streamer::stop() { running_ = false; }

bool Streamer::sample_due(std::uint32_t& index) {
  if (!running_) return false;
  if (decimation_count_ != 0) {
    if (++decimation_count_ >= config_.decimation) decimation_count_ = 0;
    return false;
  }
  if (config_.decimation > 1) decimation_count_ = 1;
  index = next_index_++;
  return true;
}

std::uint64_t Streamer::time_us_of(std::uint32_t index) const {
  const std::uint64_t tick = start_tick_ + static_cast<std::uint64_t>(index) * config_.decimation;
  return base_.us_of(tick, control_rate_Hz_);
}

void Streamer::note_gap(std::uint32_t first, std::uint32_t count, proto::GapStage stage) {
  after_gap_ = true;
  proto::EventStreamGap g;
  g.time_us = time_us_of(first);
  g.first_missing_index = first;
  g.missing_count = count;
  g.stage = stage;
  if (!gaps_.empty()) {
    // merge with the last pending event of the same stage when contiguous
    proto::EventStreamGap& last = gaps_.back();
    if (last.stage == stage && last.first_missing_index + last.missing_count == first) {
      last.missing_count += count;
      return;
    }
  }
  if (!gaps_.push(g)) {
    // the event queue is full: fold into the newest event so the count stays right
    proto::EventStreamGap& last = gaps_.back();
    last.missing_count = first + count - last.first_missing_index;
  }
}

void Streamer::accept(const IndexedSample& s) {
  if (s.index != expected_) {
    const std::uint32_t missing = s.index - expected_;
    counters_.isr_queue_overflows += missing;
    note_gap(expected_, missing, proto::GapStage::isr_queue);
  }
  expected_ = s.index + 1;
  IndexedSample in = s;
  if (after_gap_) in.sample.status |= 1u << static_cast<unsigned>(proto::StatusBit::after_gap);
  if (!backlog_.push(in)) {
    ++counters_.stream_samples_lost;
    note_gap(s.index, 1, proto::GapStage::stream_backlog);
    return;
  }
  after_gap_ = false;
  if (backlog_.size() > counters_.stream_backlog_max)
    counters_.stream_backlog_max = static_cast<std::uint32_t>(backlog_.size());
}

}  // namespace palp::fw
