// SPDX-License-Identifier: Apache-2.0
// The recorder (palp/recorder.hpp): zeroing, stream, optional program, every sample and gap into
// a recording with its sidecar; every exit path stops what it started.
#include "palp/recorder.hpp"

#include <chrono>
#include <cmath>
#include <exception>
#include <future>
#include <limits>
#include <variant>
#include <vector>

#include "palp/error.hpp"
#include "palp/result.hpp"
#include "ramp_reps.hpp"

namespace palp {

namespace {

using std::chrono::milliseconds;
using RecorderClock = std::chrono::steady_clock;

milliseconds recorder_ms(double s) { return milliseconds(static_cast<long long>(std::ceil(s * 1e3))); }

RecordingRow recorded_row(const Sample& s, int rep) {
  return {.sample_index = s.index,
          .t_s = s.t_device_s,
          .i_cmd_A = s.i_cmd_A,
          .i_A = s.i_A,
          .z_mm = static_cast<double>(s.encoder_counts) / 1e3,
          .p_Pa = s.p_Pa,
          .status = s.status,
          .rep = rep};
}

// levels of a staircase from `from` toward `to` by `step`, `to` included when on the grid
double staircase_levels(double from, double to, double step) {
  return std::floor(std::fabs(to - from) / step + 1e-3) + 1;
}

struct KindName {
  std::string operator()(const HoldProgram&) const { return "hold"; }
  std::string operator()(const RampProgram&) const { return "ramp"; }
  std::string operator()(const SineProgram&) const { return "sine"; }
  std::string operator()(const SweepProgram&) const { return "sweep"; }
};

struct DurationOf {
  double operator()(const HoldProgram& m) const { return m.duration_s; }
  double operator()(const RampProgram& m) const {
    const double levels = staircase_levels(m.start_A, m.stop_A, m.step_A);
    const double stairs = m.unload ? 2 * levels - 1 : levels;
    return stairs * m.dwell_s * m.repetitions;
  }
  double operator()(const SineProgram& m) const {
    return m.cycles > 0 ? m.cycles / static_cast<double>(m.frequency_Hz) : 0.0;
  }
  double operator()(const SweepProgram& m) const {
    double t = 0;
    const double lines = staircase_levels(m.start_Hz, m.stop_Hz, m.step_Hz);
    const double dir = m.stop_Hz >= m.start_Hz ? 1.0 : -1.0;
    for (double j = 0; j < lines; ++j) {
      const double f = m.start_Hz + dir * j * m.step_Hz;
      const double settle = std::max<double>(m.settle_cycles, std::ceil(m.settle_min_s * f));
      t += (settle + m.measure_cycles) / f;
    }
    return t;
  }
};

}  // namespace

std::string program_kind(const RecordedProgram& program) { return std::visit(KindName{}, program); }

double expected_duration_s(const RecordedProgram& program) {
  return std::visit(DurationOf{}, program);
}

struct Recorder::Impl {
  RecordSettings s;
  RecordingWriter writer;
  bool ran = false;

  Impl(RecordSettings settings, const std::filesystem::path& out, Overwrite overwrite)
      : s(std::move(settings)), writer(out, {.overwrite = overwrite}) {}
};

namespace {

// the settings' checks, before the writer claims the files
RecordSettings checked_settings(RecordSettings s) {
  if (!(s.rate_Hz > 0)) throw ConfigError("record: rate_Hz must be above 0");
  if (s.zero_current || s.zero_pressure)
    if (!(s.zero_s > 0)) throw ConfigError("record: zero_s must be above 0");
  if (!(s.duration_s >= 0)) throw ConfigError("record: duration_s must not be negative");
  if (!s.program && !(s.duration_s > 0))
    throw ConfigError("record: without a program duration_s must be above 0");
  if (s.program && !(expected_duration_s(*s.program) > 0) && !(s.duration_s > 0))
    throw ConfigError("record: the " + program_kind(*s.program) +
                      " runs until stopped with these parameters; give duration_s");
  const auto csv = recording_csv_path(s.out);
  for (const auto& f : {csv, recording_sidecar_path(csv)})
    if (s.overwrite == Overwrite::no && std::filesystem::exists(f))
      throw ConfigError(f.string() + " already exists; choose another RecordSettings::out, or set "
                        "overwrite = palp::Overwrite::yes to replace it");
  return s;
}

nlohmann::json recorded_program_parameters(const RecordedProgram& p) {
  return std::visit([](const auto& m) { return program_json(m); }, p);
}

void load_program(Probe& probe, const RecordedProgram& p) {
  std::visit([&probe](const auto& m) { probe.load(m); }, p);
}

}  // namespace

Recorder::Recorder(RecordSettings settings) {
  RecordSettings s = checked_settings(std::move(settings));
  const auto out = s.out;
  const auto overwrite = s.overwrite;
  impl_ = std::make_unique<Impl>(std::move(s), out, overwrite);
}

Recorder::~Recorder() = default;
Recorder::Recorder(Recorder&&) noexcept = default;
Recorder& Recorder::operator=(Recorder&&) noexcept = default;

RecordResult record(Probe& probe, RecordSettings settings) {
  return Recorder(std::move(settings)).run(probe);
}

RecordResult Recorder::run(Probe& probe) {
  if (impl_->ran) throw ConfigError("record: a Recorder runs once");
  impl_->ran = true;
  const RecordSettings& o = impl_->s;
  RecordingWriter& writer = impl_->writer;
  const auto& program = o.program;

  if (o.zero_current) probe.zero_current_offset(o.zero_s);
  if (o.zero_pressure) probe.zero_pressure(o.zero_s);
  const auto stream = probe.configure_stream({.rate_Hz = o.rate_Hz});
  Sidecar side = setup_sidecar(probe);
  side.device["params"] = params_json(probe.params());
  if (program) {
    side.program = {{"kind", program_kind(*program)}, {"parameters", recorded_program_parameters(*program)}};
  } else {
    side.extra["program_reason"] = o.no_program_reason;
  }

  const double stop_after_s = o.duration_s;
  double expected_s = program ? expected_duration_s(*program) : o.duration_s;
  if (stop_after_s > 0 && (expected_s <= 0 || stop_after_s < expected_s)) expected_s = stop_after_s;
  const auto expected = static_cast<std::uint64_t>(std::llround(expected_s * stream.rate_Hz));
  const std::uint64_t stop_index =
      stop_after_s > 0 ? static_cast<std::uint64_t>(std::llround(stop_after_s * stream.rate_Hz))
                       : std::numeric_limits<std::uint64_t>::max();
  std::optional<experiment::RampReps> reps;
  if (program)
    if (const auto* ramp = std::get_if<RampProgram>(&*program)) reps.emplace(*ramp);

  RecordResult out;
  nlohmann::json gaps = nlohmann::json::array();
  bool stopping = false, past_end = false;
  auto consume = [&](const std::vector<StreamItem>& items) {
    for (const auto& item : items) {
      if (const auto* g = std::get_if<Gap>(&item)) {
        out.samples_missing += g->count;
        gaps.push_back({{"first_index", g->first_index},
                        {"count", g->count},
                        {"source", gap_source_name(g->source)},
                        {"t_device_s", g->t_device_s}});
        continue;
      }
      const auto& s = std::get<Sample>(item);
      if (!program && s.index >= stop_index) {  // a stream keeps exactly duration_s of samples
        past_end = true;
        continue;
      }
      writer.append(recorded_row(s, reps ? (*reps)(s) : 0));
      ++out.samples;
      if (s.index + 1 >= stop_index) past_end = true;
    }
  };
  auto report = [&](bool finished) {
    if (o.progress) o.progress({out.samples, expected, out.samples_missing, finished});
  };

  if (o.cancelled && o.cancelled()) {  // before anything starts: nothing to record
    out.interrupted = true;
    report(true);
    out.csv = writer.csv_path();
    out.sidecar = writer.sidecar_path();
    return out;
  }
  std::exception_ptr error;
  std::future<ProgramResult> done;
  bool loaded = false, streaming = false;
  bool begun = false;  // the program started (or, without one, the stream): there is a recording
  try {
    if (program) {
      load_program(probe, *program);
      loaded = true;
    }
    streaming = true;  // from the request on: a lost reply may leave it running
    probe.start_stream();
    if (program) {
      probe.start();
      begun = true;
      const double wait_s = 2 * expected_s + 30 + o.reply_timeout_s;
      done = std::async(std::launch::async, [&probe, wait_s] { return probe.wait(recorder_ms(wait_s)); });
    }
    begun = true;
    std::vector<StreamItem> items;
    auto last_item = RecorderClock::now();
    const auto silence_limit = std::chrono::duration<double>(o.reply_timeout_s + 5);
    for (;;) {
      items.clear();
      if (auto it = probe.next(milliseconds(50))) {
        items.push_back(*it);
        probe.drain(items);
        last_item = RecorderClock::now();
      } else if (RecorderClock::now() - last_item > silence_limit) {
        throw TimeoutError("stream samples from " + probe.uri(), silence_limit.count(),
                           probe.health());
      }
      consume(items);
      report(false);
      if (!out.interrupted && o.cancelled && o.cancelled()) {
        out.interrupted = true;
        if (!program) break;
      }
      if (!program && past_end) break;
      if (program && !stopping && (out.interrupted || past_end)) {
        stopping = true;
        probe.stop();
      }
      if (program && done.wait_for(milliseconds(0)) == std::future_status::ready) {
        out.program = done.get();
        break;
      }
    }
  } catch (...) {
    error = std::current_exception();
  }
  // leave the device quiet, keep what is still queued, and write the recording: each step on its
  // own, so that one failing (a lost reply) does not skip the others; the first error is kept
  auto attempt = [&error](auto&& step) {
    try {
      step();
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  };
  if (loaded) attempt([&] { probe.stop(); });  // the coil back to 0 A (an ended program: no-op)
  if (done.valid()) attempt([&] { done.wait(); });
  if (streaming)
    attempt([&] {
      probe.stop_stream();
      while (auto it = probe.next(milliseconds(100))) consume({*it});
    });
  if (error && loaded) attempt([&] { probe.make_safe(); });  // no program, 0 A, no stream
  attempt([&] { side.extra["health"] = health_json(probe.health()); });
  if (program) {
    side.program["result"] = out.program ? program_result_json(*out.program) : nlohmann::json(nullptr);
    if (!out.program) attempt([&] { side.program["fault"] = fault_json(probe.fault()); });
  }
  report(true);
  out.gaps = gaps.size();
  side.extra["gaps"] = std::move(gaps);
  side.extra["samples_missing"] = out.samples_missing;
  side.extra["interrupted"] = out.interrupted;
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      side.extra["error"] = e.what();
    }
  }
  out.csv = writer.csv_path();
  out.sidecar = writer.sidecar_path();
  if (begun && writer.rows() > 0) {
    out.sidecar_written = writer.finish(side);
    out.written = true;
  }
  if (error) std::rethrow_exception(error);
  return out;
}

}  // namespace palp
