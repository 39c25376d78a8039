// SPDX-License-Identifier: Apache-2.0
#include "live_stream.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <string>
#include <variant>
#include <vector>

#include "common.hpp"

namespace palpctl {

namespace {
using LiveClock = std::chrono::steady_clock;

// Means over bins of `size` samples, written as the samples event's columns.
class Binner {
 public:
  explicit Binner(std::size_t size) : size_(size) {}

  void add(const palp::Sample& s) {
    ++n_;
    t_ += s.t_device_s;
    i_cmd_ += s.i_cmd_A;
    i_ += s.i_A;
    z_ += mm_from_m(s.z_m);
    for (std::size_t k = 0; k < 6; ++k) p_[k] += s.p_Pa[k];
    if (n_ >= size_) flush();
  }
  /// Ends the bin in progress (before a gap) and adds the gap's null point.
  void gap(double t_device_s) {
    flush();
    point(t_device_s, nullptr);
  }
  /// The event's data, then empty columns for the next push (a partial bin stays for it).
  std::string take() {
    std::string j = "{\"t_s\":[" + cols_[0] + "],\"i_cmd_A\":[" + cols_[1] + "],\"i_A\":[" +
                    cols_[2] + "],\"z_mm\":[" + cols_[3] + "],\"p_Pa\":[";
    for (std::size_t k = 0; k < 6; ++k) j += (k > 0 ? ",[" : "[") + cols_[4 + k] + "]";
    j += "]}";
    for (auto& c : cols_) c.clear();
    return j;
  }

 private:
  void flush() {
    if (n_ == 0) return;
    const double n = static_cast<double>(n_);
    const std::array<double, 10> v = {i_cmd_ / n, i_ / n, z_ / n, p_[0] / n, p_[1] / n,
                                      p_[2] / n,  p_[3] / n, p_[4] / n, p_[5] / n, 0};
    point(t_ / n, v.data());
    n_ = 0;
    t_ = i_cmd_ = i_ = z_ = 0;
    p_ = {};
  }
  // v: i_cmd, i, z, p1..p6; nullptr: a null point (a gap)
  void point(double t_s, const double* v) {
    static constexpr const char* kFormat[9] = {"%.5g", "%.5g", "%.5f", "%.2f", "%.2f",
                                               "%.2f", "%.2f", "%.2f", "%.2f"};
    char buf[48];
    append(0, (std::snprintf(buf, sizeof buf, "%.5f", t_s), buf));
    for (std::size_t k = 0; k < 9; ++k) {
      if (v == nullptr || !std::isfinite(v[k])) {
        append(1 + k, "null");
      } else {
        std::snprintf(buf, sizeof buf, kFormat[k], v[k]);
        append(1 + k, buf);
      }
    }
  }
  void append(std::size_t col, const char* text) {
    if (!cols_[col].empty()) cols_[col] += ',';
    cols_[col] += text;
  }

  std::size_t size_;
  std::size_t n_ = 0;
  double t_ = 0, i_cmd_ = 0, i_ = 0, z_ = 0;
  std::array<double, 6> p_{};
  std::array<std::string, 10> cols_;  // t, i_cmd, i, z, p1..p6
};

std::string quoted_json(const std::string& s) { return json(s).dump(); }
}  // namespace

LiveStreamTotals run_live_stream(palp::Probe& probe, LiveServer& server,
                                 const LiveStreamOptions& o) {
  const auto bin = static_cast<std::size_t>(std::max(1.0, std::ceil(o.rate_Hz / kPointsPerS)));
  Binner binner(bin);
  LiveStreamTotals totals;
  const auto t0 = LiveClock::now();
  const auto push_period = std::chrono::duration_cast<LiveClock::duration>(
      std::chrono::duration<double>(1.0 / kPushHz));
  const auto status_period = std::chrono::duration_cast<LiveClock::duration>(
      std::chrono::duration<double>(1.0 / kStatusHz));
  auto next_push = t0;
  auto next_status = t0;
  bool have_status = false;
  palp::Status last{};
  std::deque<std::pair<LiveClock::time_point, std::uint64_t>> recent;  // samples/s over ~1 s
  std::vector<palp::StreamItem> items;

  while (!interrupted()) {
    next_push += push_period;
    auto now = LiveClock::now();
    if (next_push < now - push_period) next_push = now;  // fell behind: no burst to catch up
    server.serve(std::chrono::duration_cast<std::chrono::milliseconds>(next_push - now));
    if (interrupted()) break;
    now = LiveClock::now();

    items.clear();
    probe.drain(items);
    std::vector<std::string> gap_events;
    std::uint64_t n = 0;
    for (const auto& item : items) {
      if (const auto* g = std::get_if<palp::Gap>(&item)) {
        binner.gap(g->t_device_s);
        totals.samples_lost += g->count;
        ++totals.gaps;
        gap_events.push_back("{\"t_device_s\":" + json(g->t_device_s).dump() +
                             ",\"count\":" + std::to_string(g->count) + ",\"source\":" +
                             quoted_json(palp::gap_source_name(g->source)) + "}");
      } else {
        binner.add(std::get<palp::Sample>(item));
        ++n;
      }
    }
    totals.samples += n;
    ++totals.pushes;
    server.broadcast("samples", binner.take());
    for (const auto& g : gap_events) server.broadcast("gap", g);
    recent.emplace_back(now, n);
    while (recent.size() > 1 && now - recent.front().first > std::chrono::seconds(1))
      recent.pop_front();

    if (now >= next_status) {
      next_status = now + status_period;
      const palp::Status st = probe.status();
      if (have_status && (st.state != last.state || st.fault != last.fault))
        server.broadcast("state", json{{"t_device_s", st.t_device_s},
                                       {"state", name_of(st.state)},
                                       {"fault", name_of(st.fault)},
                                       {"previous_state", name_of(last.state)},
                                       {"previous_fault", name_of(last.fault)}}
                                      .dump());
      last = st;
      have_status = true;
      std::uint64_t in_window = 0;  // the samples of the pushes after the first in recent
      for (std::size_t k = 1; k < recent.size(); ++k) in_window += recent[k].second;
      const double span =
          std::chrono::duration<double>(recent.back().first - recent.front().first).count();
      server.broadcast("status",
                       json{{"t_device_s", st.t_device_s},
                            {"state", name_of(st.state)},
                            {"fault", name_of(st.fault)},
                            {"program", name_of(st.program)},
                            {"samples_per_s",
                             span > 0 ? static_cast<double>(in_window) / span : 0.0},
                            {"samples_lost", totals.samples_lost},
                            {"gaps", totals.gaps},
                            {"rate_Hz", o.rate_Hz},
                            {"points_per_s", o.rate_Hz / static_cast<double>(bin)},
                            {"push_Hz", kPushHz},
                            {"clients", server.event_clients()}}
                           .dump());
    }
    if (o.seconds > 0 && now - t0 >= std::chrono::duration<double>(o.seconds)) break;
  }
  totals.seconds = std::chrono::duration<double>(LiveClock::now() - t0).count();
  return totals;
}

}  // namespace palpctl
