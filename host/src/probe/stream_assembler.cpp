// SPDX-License-Identifier: Apache-2.0
#include "probe/stream_assembler.hpp"

#include <cmath>

namespace palp::detail {

Sample to_sample(const proto::RawSample& raw, std::uint64_t index, double t_device_s,
                 double t_host_s) {
  Sample s;
  s.index = index;
  s.t_device_s = t_device_s;
  s.t_host_s = t_host_s;
  s.i_cmd_A = raw.i_cmd * proto::kCurrentLsb_A;
  s.i_A = raw.i_meas * proto::kCurrentLsb_A;
  s.encoder_counts = raw.encoder;
  s.z_m = raw.encoder * 1e-6;
  for (std::size_t k = 0; k < 6; ++k) s.p_Pa[k] = raw.pressure[k] * proto::kPressureLsb_Pa;
  s.status = raw.status;
  s.v_cmd_V = raw.v_cmd * proto::kVoltageLsb_V;
  return s;
}

void StreamAssembler::restart() {
  expected_ = 0;
  wire_expected_ = 0;
  any_ = false;
  reconnect_pending_ = false;
  pending_.clear();
}

void StreamAssembler::reconnected() {
  reconnect_pending_ = true;
  t_before_reconnect_s_ = next_t_s_;
  wire_expected_ = 0;
  pending_.clear();
}

void StreamAssembler::device_gap(const proto::EventStreamGap& g) {
  if (g.missing_count == 0) return;
  pending_.push_back({g.first_missing_index, g.missing_count, g.stage,
                      static_cast<double>(g.time_us) * 1e-6});
}

namespace {
GapSource source_of(proto::GapStage s) {
  switch (s) {
    case proto::GapStage::isr_queue: return GapSource::isr_queue;
    case proto::GapStage::stream_backlog: return GapSource::stream_backlog;
    case proto::GapStage::usb_in: return GapSource::usb_in;
    case proto::GapStage::transport: return GapSource::transport;
  }
  return GapSource::transport;
}
}  // namespace

// Missing wire indices [wire_expected_, wire_upto): device-reported runs keep their stage, the
// rest is the transport's. Pending runs that end before wire_expected_ were already delivered.
void StreamAssembler::emit_gaps(std::uint32_t wire_upto, std::vector<StreamItem>& out) {
  auto add = [&](std::uint32_t n, GapSource src) {
    if (n == 0) return;
    Gap g;
    g.first_index = expected_;
    g.count = n;
    g.source = src;
    g.t_device_s = next_t_s_;
    out.emplace_back(g);
    expected_ += n;
    wire_expected_ += n;
    next_t_s_ += n * period_s_;
  };
  while (wire_expected_ != wire_upto) {
    const std::uint32_t left = wire_upto - wire_expected_;
    // the first pending run that is not entirely behind us
    while (!pending_.empty()) {
      const Pending& p = pending_.front();
      const std::uint32_t end_rel = p.wire_first + p.count - wire_expected_;
      if (end_rel == 0 || end_rel > 0x80000000u) pending_.pop_front();
      else break;
    }
    if (pending_.empty()) {
      add(left, GapSource::transport);
      break;
    }
    Pending& p = pending_.front();
    const std::uint32_t start_rel = p.wire_first - wire_expected_;
    if (start_rel < 0x80000000u && start_rel > 0) {  // transport loss before the device's run
      add(std::min(start_rel, left), GapSource::transport);
      continue;
    }
    // wire_expected_ lies inside p
    const std::uint32_t inside = p.wire_first + p.count - wire_expected_;
    add(std::min(inside, left), source_of(p.stage));
  }
}

bool StreamAssembler::batch(const proto::SampleBatch& b,
                            const std::function<double(double)>& to_host,
                            std::vector<StreamItem>& out) {
  if (proto::check_batch(b) != proto::BatchProblem::none) {
    ++rejected_;
    return false;
  }
  const double period_s = b.period_ns * 1e-9;
  const double first_t_s = static_cast<double>(b.first_time_us) * 1e-6;
  if (reconnect_pending_) {
    Gap g;
    g.first_index = expected_;
    g.source = GapSource::reconnect;
    g.t_device_s = t_before_reconnect_s_;
    if (any_ && first_t_s > t_before_reconnect_s_ && period_s > 0) {
      g.count = static_cast<std::uint64_t>(std::llround((first_t_s - t_before_reconnect_s_) / period_s));
    } else {
      g.count = 0;
      g.count_known = !any_;
    }
    if (g.count > 0 || !g.count_known) out.emplace_back(g);
    expected_ += g.count;
    wire_expected_ = 0;
    reconnect_pending_ = false;
    any_ = true;
  }
  const std::uint32_t ahead = b.first_index - wire_expected_;
  if (ahead >= 0x80000000u) {  // behind: indices already delivered
    ++rejected_;
    return false;
  }
  period_s_ = period_s;
  if (!any_ || ahead == 0) next_t_s_ = first_t_s - ahead * period_s;
  any_ = true;
  emit_gaps(b.first_index, out);
  proto::Reader r(b.data.items.data(), b.data.size);
  for (std::uint16_t k = 0; k < b.sample_count; ++k) {
    proto::RawSample raw;
    proto::unpack_sample(r, raw, b.channels);
    const double t = first_t_s + k * period_s;
    out.emplace_back(to_sample(raw, expected_, t, to_host(t)));
    ++expected_;
    ++wire_expected_;
  }
  next_t_s_ = first_t_s + b.sample_count * period_s;
  return true;
}

}  // namespace palp::detail
