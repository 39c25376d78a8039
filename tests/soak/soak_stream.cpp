// SPDX-License-Identifier: Apache-2.0
// palp-soak: a long stream at 10 kHz from palp-sim linked in (virtual time, as fast as the SDK
// reads) with frames dropped and corrupted on the way to the host, and the audit of
// docs/reliability.md section 7:
//   1. every sample index is either delivered once, in order, or inside exactly one reported gap;
//   2. the SDK's counters agree with what the application received (samples, gaps, missing);
//   3. the transport agrees with the simulator and the device: every corrupted frame is rejected,
//      every frame the device sent is received, dropped or rejected; the device lost nothing;
//   4. the recording holds every delivered sample (rows, indices) and the gaps in its sidecar;
//   5. memory is flat: resident set size sampled over the run.
// Prints the figures and "audit: pass" (exit 0) or each failed check (exit 1).
//
// Virtual time runs as fast as the SDK's I/O thread reads, not as fast as this program consumes:
// with --record (every column, ~80 bytes a row) the writer may fall behind, the SDK's queue fills
// (1M items) and drops, and those samples are host_queue gaps - audited like the transport's.
//
//   palp-soak --seconds 3600 --drop-frames 97 --corrupt-frames 89 --record /tmp/soak/run
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "palp/probe.hpp"
#include "palp/recording.hpp"
#include "palp/sim_inproc.hpp"

namespace {

struct Options {
  double seconds = 60;
  unsigned drop = 97, corrupt = 89;
  std::string record;  // empty: no recording
};

double rss_MB() {
  std::ifstream f("/proc/self/statm");
  long pages = 0, resident = 0;
  f >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
}

/// "key=value" pairs of palp-sim's status line.
std::map<std::string, std::string> status_fields(const std::string& line) {
  std::map<std::string, std::string> m;
  std::istringstream in(line);
  std::string word;
  while (in >> word) {
    const auto eq = word.find('=');
    if (eq != std::string::npos) m[word.substr(0, eq)] = word.substr(eq + 1);
  }
  return m;
}

class Audit {
 public:
  void sample(const palp::Sample& s) {
    if (s.index < next_) ++duplicates_;
    if (s.index > next_) unreported_ += s.index - next_;
    next_ = s.index + 1;
    ++received_;
  }
  void gap(const palp::Gap& g) {
    if (g.first_index < next_) ++overlapping_;
    if (g.first_index > next_) unreported_ += g.first_index - next_;
    next_ = g.first_index + g.count;
    ++gaps_;
    missing_ += g.count;
    if (g.source == palp::GapSource::transport) transport_missing_ += g.count;
    else if (g.source == palp::GapSource::host_queue) queue_missing_ += g.count;
    else ++other_sources_;
    if (keep_gaps_) gap_list_.push_back(g);  // for the recording's sidecar only
  }
  bool keep_gaps_ = false;
  std::uint64_t next_ = 0, received_ = 0, unreported_ = 0, duplicates_ = 0, overlapping_ = 0, gaps_ = 0,
                missing_ = 0, transport_missing_ = 0, queue_missing_ = 0, other_sources_ = 0;
  std::vector<palp::Gap> gap_list_;
};

int failures = 0;
void check(bool ok, const std::string& what) {
  std::printf("  %s %s\n", ok ? "ok  " : "FAIL", what.c_str());
  if (!ok) ++failures;
}
std::string u(std::uint64_t v) { return std::to_string(v); }

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (k + 1 >= argc) {
      std::fprintf(stderr, "palp-soak: %s needs a value\n", a.c_str());
      std::exit(2);
    }
    const std::string v = argv[++k];
    if (a == "--seconds") o.seconds = std::stod(v);
    else if (a == "--drop-frames") o.drop = static_cast<unsigned>(std::stoul(v));
    else if (a == "--corrupt-frames") o.corrupt = static_cast<unsigned>(std::stoul(v));
    else if (a == "--record") o.record = v;
    else {
      std::fprintf(stderr,
                   "usage: palp-soak [--seconds S] [--drop-frames N] [--corrupt-frames N] [--record PATH]\n");
      std::exit(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  constexpr double kRate_Hz = 10000;
  const auto t0 = std::chrono::steady_clock::now();
  palp::sim::InprocSimulator sim({.phantom = "none"});
  palp::Probe probe(sim.transport());
  probe.configure_stream({.rate_Hz = kRate_Hz});
  std::optional<palp::RecordingWriter> writer;
  if (!o.record.empty()) writer.emplace(o.record, palp::WriterOptions{.overwrite = palp::Overwrite::yes});
  for (const std::string& c : {"drop-frames " + std::to_string(o.drop), "corrupt-frames " + std::to_string(o.corrupt)})
    if (sim.control(c).rfind("ok", 0) != 0) {
      std::fprintf(stderr, "palp-soak: %s refused\n", c.c_str());
      return 2;
    }
  probe.start_stream();

  Audit audit;
  audit.keep_gaps_ = writer.has_value();
  const auto target = static_cast<std::uint64_t>(o.seconds * kRate_Hz);
  std::vector<double> rss;  // at every tenth of the run
  std::vector<palp::StreamItem> items;
  auto take = [&](const palp::StreamItem& item) {
    if (const auto* s = std::get_if<palp::Sample>(&item)) {
      audit.sample(*s);
      if (writer)
        writer->append({.sample_index = s->index, .t_s = s->t_device_s, .i_cmd_A = s->i_cmd_A, .i_A = s->i_A,
                        .z_mm = s->z_m * 1e3, .p_Pa = s->p_Pa, .status = s->status});
    } else {
      audit.gap(std::get<palp::Gap>(item));
    }
  };
  while (audit.next_ < target) {
    items.clear();
    if (auto first = probe.next(std::chrono::milliseconds(2000))) items.push_back(*first);
    else break;  // a stalled stream: the audit below says so
    probe.drain(items, 4096);  // bounded: this vector is not a second queue
    for (const auto& item : items) take(item);
    if (audit.next_ * 10 >= target * (rss.size() + 1) || rss.empty()) rss.push_back(rss_MB());
  }
  // the knobs off for the health round trip; then every frame still in flight
  sim.control("drop-frames 0");
  sim.control("corrupt-frames 0");
  probe.stop_stream();
  while (auto item = probe.next(std::chrono::milliseconds(200))) take(*item);
  const palp::HealthCounters h = probe.health();
  const auto st = status_fields(sim.control("status"));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rss.push_back(rss_MB());

  std::printf("palp-soak: %.0f s of device time at 10 kHz, drop-frames %u, corrupt-frames %u\n", o.seconds, o.drop,
              o.corrupt);
  std::printf("  wall time %.1f s (%.1fx real time)\n", wall_s, audit.next_ / kRate_Hz / wall_s);
  std::printf("  samples: indices 0..%llu, delivered %llu, in %llu gaps %llu\n",
              static_cast<unsigned long long>(audit.next_ ? audit.next_ - 1 : 0),
              static_cast<unsigned long long>(audit.received_), static_cast<unsigned long long>(audit.gaps_),
              static_cast<unsigned long long>(audit.missing_));
  std::printf("  simulator: frames_out %s dropped %s corrupted %s\n", st.at("frames_out").c_str(),
              st.at("dropped").c_str(), st.at("corrupted").c_str());
  std::printf("  %s\n", palp::describe(h).c_str());
  std::printf("  RSS MB at each tenth:");
  for (double r : rss) std::printf(" %.1f", r);
  std::printf("\n");

  std::printf("audit:\n");
  check(audit.next_ >= target, "the stream reached " + u(target) + " samples (next index " + u(audit.next_) + ")");
  check(audit.unreported_ == 0, "no sample missing outside a reported gap (" + u(audit.unreported_) + ")");
  check(audit.duplicates_ == 0 && audit.overlapping_ == 0,
        "no sample twice, no gap over a delivered sample (" + u(audit.duplicates_) + ", " + u(audit.overlapping_) + ")");
  check(audit.received_ + audit.missing_ == audit.next_, "delivered + missing = indices (" + u(audit.received_) +
                                                             " + " + u(audit.missing_) + " = " + u(audit.next_) + ")");
  check(h.host_samples_received == audit.received_ + h.host_queue_dropped,
        "SDK samples_received = delivered + queue_dropped (" + u(h.host_samples_received) + " = " +
            u(audit.received_) + " + " + u(h.host_queue_dropped) + ")");
  check(h.host_samples_missing == audit.missing_ && h.host_gaps == audit.gaps_,
        "SDK samples_missing and gaps = the gap records (" + u(h.host_samples_missing) + ", " + u(h.host_gaps) + ")");
  check(audit.queue_missing_ == h.host_queue_dropped && audit.other_sources_ == 0,
        "gaps: transport " + u(audit.transport_missing_) + " samples, host_queue " + u(audit.queue_missing_) +
            " = SDK queue_dropped (the application fell behind), no other source");
  check(h.device_valid && h.stream_samples_lost == 0 && h.isr_queue_overflows == 0 && h.device_stream_gaps == 0,
        "the device lost no sample itself");
  const std::uint64_t dropped = std::stoull(st.at("dropped")), corrupted = std::stoull(st.at("corrupted"));
  check(dropped > 0 && corrupted > 0, "the knobs were on (" + u(dropped) + " dropped, " + u(corrupted) + " corrupted)");
  // a flipped bit damages its frame and, when it hits a delimiter or makes one, the frame next
  // to it too (two frames read as one, or one as two): each corruption costs 1 or 2 frames
  // every corrupted frame is rejected (palp-sim never corrupts a delimiter); the device's own count
  // of frames sent is from its health reply, and the host's counters are read as that reply
  // arrives: the reply itself is in the host's count only, and a frame in flight (a heartbeat's
  // Ack) may be in one count and not yet the other
  check(h.host_rx_rejected == corrupted, "host rejected = corrupted (" + u(h.host_rx_rejected) + ")");
  constexpr std::uint64_t kInFlight = 2;
  const std::uint64_t sent = h.device_frames_tx;
  check(h.host_frames_rx + dropped + corrupted <= sent + 1 &&
            h.host_frames_rx + dropped + corrupted + kInFlight >= sent,
        "host received + dropped + corrupted = device sent (+1: the reply), " + u(kInFlight) + " in flight at most (" +
            u(h.host_frames_rx) + " + " + u(dropped) + " + " + u(corrupted) + " of " + u(sent) + ")");
  if (writer) {
    palp::Sidecar side;
    nlohmann::json gaps = nlohmann::json::array();
    for (const palp::Gap& g : audit.gap_list_) gaps.push_back({{"first_index", g.first_index}, {"count", g.count}});
    side.extra["gaps"] = gaps;
    writer->finish(side);
    const palp::Sidecar back = palp::read_sidecar(palp::recording_sidecar_path(palp::recording_csv_path(o.record)));
    check(back.csv_rows && *back.csv_rows == audit.received_,
          "recording rows = delivered (" + u(back.csv_rows.value_or(0)) + ")");
    check(back.extra.at("gaps").size() == audit.gaps_, "recording sidecar gaps = gap records");
    if (audit.received_ <= 2'000'000) {  // read it back whole when that is cheap
      const palp::Recording r = palp::read_recording(palp::recording_csv_path(o.record));
      std::uint64_t jumps = 0;
      for (std::size_t k = 1; k < r.sample_index->size(); ++k) jumps += (*r.sample_index)[k] - (*r.sample_index)[k - 1] - 1;
      check(jumps + (*r.sample_index)[0] + (audit.next_ - 1 - r.sample_index->back()) == audit.missing_,
            "recording index jumps = missing (" + u(jumps) + ")");
    }
  }
  // flat: what it grew by after the first tenth is at most the SDK queue's high-water mark (the
  // application fell behind for a moment) and 16 MB
  const double growth = rss.back() - rss[std::min<std::size_t>(1, rss.size() - 1)];
  const double allowed = 16.0 + static_cast<double>(h.host_queue_max * sizeof(palp::StreamItem)) / 1e6;
  char b[160];
  std::snprintf(b, sizeof b, "memory flat: RSS grew %.1f MB from the first tenth to the end (allowed %.1f MB)", growth,
                allowed);
  check(growth < allowed, b);
  std::printf("audit: %s\n", failures == 0 ? "pass" : "FAIL");
  return failures == 0 ? 0 : 1;
}
