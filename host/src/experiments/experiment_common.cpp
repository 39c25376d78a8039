// SPDX-License-Identifier: Apache-2.0
// Shared by the experiments: see experiment_common.hpp.
#include "experiment_common.hpp"

#include <charconv>
#include <chrono>
#include <cmath>
#include <exception>
#include <future>
#include <thread>
#include <variant>

#include "palp/result.hpp"

namespace palp::experiment {

namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;

constexpr unsigned kRunningBit = 1u << static_cast<unsigned>(proto::StatusBit::program_running);

milliseconds ms_from_s(double s) { return milliseconds(static_cast<long long>(std::ceil(s * 1e3))); }

RecordingRow row_of(const Sample& s) {
  return {.sample_index = s.index,
          .t_s = s.t_device_s,
          .i_cmd_A = s.i_cmd_A,
          .i_A = s.i_A,
          .z_mm = static_cast<double>(s.encoder_counts) * 1e-3,
          .p_Pa = s.p_Pa,
          .status = s.status,
          .rep = 0};
}

}  // namespace

std::string depth_key(double depth_m) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, std::round(depth_m * 1e9) / 1e6);
  return std::string(buf, r.ptr) + "_mm";
}

void wait_device_time(Probe& probe, double until_s, const std::function<bool()>& cancelled) {
  while (probe.status().t_device_s < until_s) {
    if (cancelled && cancelled()) return;
    std::this_thread::sleep_for(1ms);
  }
}

ContactEvent float_coil(Probe& probe, double current_A, const std::string& hint) {
  ContactWatchProgram w;
  w.hold_current_A = static_cast<float>(current_A);
  w.threshold_counts = kFloatCounts;
  w.timeout_s = 5.0f;
  probe.load(w);
  probe.start();
  auto event = probe.wait_contact(10s);
  if (!event) {
    // the EventContact may be lost (a device frame like any other): the watch's status says
    // whether it fired; the time and position are then those of the status read after it
    const proto::ProgramStatus ps = probe.program_status();
    if (ps.kind == proto::ProgramKind::contact_watch && ps.state == proto::ProgramState::finished &&
        ps.end == proto::ProgramEnd::contact) {
      const Status st = probe.status();
      event = ContactEvent{st.t_device_s, st.encoder_counts, 0, 0};
    }
  }
  if (!event)
    throw TimeoutError("the coil to float off its rear stop at " + std::to_string(current_A) +
                           " A (" + hint + ")",
                       10.0, std::nullopt);
  return *event;
}

bool release_coil(Probe& probe, double settle_s, const std::function<bool()>& cancelled,
                  const std::function<void()>& announce) {
  const Status st = probe.status();
  if (st.program_state != proto::ProgramState::running && std::fabs(st.i_cmd_A) <= 1e-3) return false;
  if (announce) announce();
  probe.stop();
  wait_device_time(probe, st.t_device_s + settle_s, cancelled);
  return true;
}

ProgramRecording record_program(Probe& probe, const std::function<void()>& load_and_start,
                                double expected_s,
                                const std::function<void(double, const Sample&)>& progress,
                                const std::function<bool()>& cancelled) {
  ProgramRecording out;
  std::vector<Sample> samples;
  std::exception_ptr error;
  std::future<ProgramResult> done;
  bool streaming = false;
  try {
    probe.start_stream();
    streaming = true;
    load_and_start();
    const double wait_s = 2 * expected_s + 30;
    done = std::async(std::launch::async, [&probe, wait_s] { return probe.wait(ms_from_s(wait_s)); });
    std::vector<StreamItem> items;
    double t0 = -1;
    auto last_report = Clock::now();
    bool stopping = false;
    for (;;) {
      items.clear();
      if (auto it = probe.next(20ms)) {
        items.push_back(*it);
        probe.drain(items);
      }
      for (const auto& item : items) {
        if (const auto* g = std::get_if<Gap>(&item)) {
          out.samples_missing += g->count;
          out.gaps.push_back({{"first_index", g->first_index},
                              {"count", g->count},
                              {"source", gap_source_name(g->source)},
                              {"t_device_s", g->t_device_s}});
        } else {
          const auto& s = std::get<Sample>(item);
          if ((s.status & kRunningBit) == 0) continue;  // before the program or after its end
          if (t0 < 0) t0 = s.t_device_s;
          samples.push_back(s);
        }
      }
      if (progress && !samples.empty() && Clock::now() - last_report > 200ms) {
        last_report = Clock::now();
        progress(samples.back().t_device_s - t0, samples.back());
      }
      if (!stopping && cancelled && cancelled()) {
        stopping = true;
        out.interrupted = true;
        probe.stop();
      }
      if (done.wait_for(0ms) == std::future_status::ready) {
        out.program = done.get();
        break;
      }
    }
  } catch (...) {
    error = std::current_exception();
  }
  // the coil back to 0 A, and the rest of the stream
  try {
    probe.stop();
    if (done.valid()) done.wait();
    if (streaming) {
      probe.stop_stream();
      while (auto it = probe.next(100ms))
        if (const auto* s = std::get_if<Sample>(&*it); s && (s->status & kRunningBit) != 0)
          samples.push_back(*s);
    }
  } catch (...) {
    if (!error) error = std::current_exception();
  }
  if (error) std::rethrow_exception(error);
  for (const Sample& s : samples) out.recording.append(row_of(s));
  return out;
}

Sidecar base_sidecar(Probe& probe, const std::string& experiment, const ProgramRecording& r) {
  Sidecar side = setup_sidecar(probe);
  side.extra["experiment"] = experiment;
  side.extra["gaps"] = r.gaps;
  side.extra["samples_missing"] = r.samples_missing;
  side.extra["interrupted"] = r.interrupted;
  return side;
}

}  // namespace palp::experiment
