// The quasi-static indentation (experiments.hpp): zero pressures, float the coil, stream the
// device's staircase ramp into a recording, analyse it.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <exception>
#include <future>
#include <thread>
#include <variant>
#include <vector>

#include "palp/experiments.hpp"
#include "palp/result.hpp"

namespace palp {

namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;

constexpr unsigned kRunningBit = 1u << static_cast<unsigned>(proto::StatusBit::program_running);
constexpr std::uint32_t kFloatCounts = 500;  // the coil left its rear stop (0.5 mm)
constexpr double kCountM = 1e-6;

milliseconds ms_from_s(double s) { return milliseconds(static_cast<long long>(std::ceil(s * 1e3))); }

/// The shortest decimal of a protocol f32 as a double (0.01f reads 0.01, not 0.009999999776).
double f32(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  double d = 0;
  std::from_chars(buf, r.ptr, d);
  return d;
}

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

void wait_device_time(Probe& probe, double until_s, const std::function<bool()>& cancelled) {
  while (probe.status().t_device_s < until_s) {
    if (cancelled && cancelled()) return;
    std::this_thread::sleep_for(1ms);
  }
}

/// Floats the coil at the ramp's start current and lets it settle on the specimen; returns the
/// encoder position it rests at, m.
double float_coil(Probe& probe, const IndentationSettings& s, const std::function<bool()>& cancelled) {
  ContactWatchProgram w;
  w.hold_current_A = static_cast<float>(s.start_A);
  w.threshold_counts = kFloatCounts;
  w.timeout_s = 5.0f;
  probe.load(w);
  probe.start();
  const auto event = probe.wait_contact(10s);
  if (!event)
    throw TimeoutError("the coil to float off its rear stop at " + std::to_string(s.start_A) +
                           " A (is the tip pressed against the specimen, or start_A below the "
                           "float current?)",
                       10.0, std::nullopt);
  wait_device_time(probe, event->t_device_s + s.settle_s, cancelled);
  return probe.status().encoder_counts * kCountM;
}

nlohmann::json ramp_json(const IndentationSettings& s) {
  const RampProgram m = s.ramp_program();
  return {{"start_A", f32(m.start_A)},
          {"stop_A", f32(m.stop_A)},
          {"step_A", f32(m.step_A)},
          {"dwell_s", f32(m.dwell_s)},
          {"reps", m.repetitions},
          {"unload", m.unload != 0},
          {"displacement_limit_mm", s.displacement_limit_m * 1e3}};
}

}  // namespace

IndentationRun indent(Probe& probe, const IndentationSettings& settings,
                      const IndentProgressFn& progress, const std::function<bool()>& cancelled) {
  settings.validate();
  IndentationRun run;
  run.settings = settings;
  run.device = probe.info();
  auto report = [&](const char* phase, double fraction, const Sample* last) {
    if (!progress) return;
    IndentProgress p;
    p.phase = phase;
    p.fraction = std::clamp(fraction, 0.0, 1.0);
    if (last != nullptr) {
      p.z_m = last->z_m;
      p.i_A = last->i_A;
    }
    progress(p);
  };

  // the coil at 0 A and at rest first: a program left running, or a contact watch that ended
  // holding its current (the toucher's float), would load the specimen while the pressures are
  // zeroed and keep the coil from leaving its rear stop when it is floated again
  if (const Status st = probe.status();
      st.program_state == proto::ProgramState::running || std::fabs(st.i_cmd_A) > 1e-3) {
    report("releasing the coil", 0, nullptr);
    probe.stop();
    wait_device_time(probe, st.t_device_s + settings.settle_s, cancelled);
  }
  if (settings.zero_pressure) {
    report("zeroing pressures", 0, nullptr);
    probe.zero_pressure(settings.zero_pressure_s);
  }
  const StreamInfo stream = probe.configure_stream({.rate_Hz = settings.stream_rate_Hz});

  std::vector<Sample> samples;
  nlohmann::json gaps = nlohmann::json::array();
  std::exception_ptr error;
  std::future<ProgramResult> done;
  bool streaming = false;
  try {
    report("floating the coil", 0, nullptr);
    run.float_z_m = float_coil(probe, settings, cancelled);
    if (cancelled && cancelled()) {
      run.interrupted = true;
    } else {
      probe.start_stream();
      streaming = true;
      probe.load(settings.ramp_program());
      probe.start();
      const double wait_s = 2 * settings.ramp_duration_s() + 30;
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
            run.samples_missing += g->count;
            gaps.push_back({{"first_index", g->first_index},
                            {"count", g->count},
                            {"source", gap_source_name(g->source)},
                            {"t_device_s", g->t_device_s}});
          } else {
            const auto& s = std::get<Sample>(item);
            if ((s.status & kRunningBit) == 0) continue;  // before the ramp or after its end
            if (t0 < 0) t0 = s.t_device_s;
            samples.push_back(s);
          }
        }
        if (!samples.empty() && Clock::now() - last_report > 200ms) {
          last_report = Clock::now();
          report("ramp", (samples.back().t_device_s - t0) / settings.ramp_duration_s(), &samples.back());
        }
        if (!stopping && cancelled && cancelled()) {
          stopping = true;
          run.interrupted = true;
          probe.stop();
        }
        if (done.wait_for(0ms) == std::future_status::ready) {
          run.program = done.get();
          break;
        }
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
  if (!samples.empty()) report("ramp", 1.0, &samples.back());

  Recording& rec = run.recording;
  for (const Sample& s : samples) rec.append(row_of(s));
  if (rec.size() > 0) {
    rec.rep = split_repetitions_at_current_minima(*rec.i_cmd_A);
  }

  Sidecar side;
  side.program = {{"kind", "ramp"},
                  {"parameters", ramp_json(settings)},
                  {"result",
                   {{"end", proto::enum_name(run.program.end) ? proto::enum_name(run.program.end) : "?"},
                    {"t_device_s", run.program.t_device_s},
                    {"repetitions_done", run.program.repetitions_done}}}};
  side.device = device_json(run.device);
  side.device["uri"] = probe.uri();
  const Calibration cal = probe.calibration();
  side.calibration = calibration_json(cal);
  if (cal.stroke_origin_valid != 0) {
    side.stroke_origin_z_mm = cal.stroke_origin_counts * 1e-3;
  } else {
    side.stroke_origin_z_mm_reason = "the device's stroke origin is not homed (palpctl calibrate home)";
  }
  for (const auto& z : probe.zeroing()) side.zeroing.push_back(zeroing_json(z));
  side.extra["experiment"] = "indentation";
  side.extra["stream"] = {{"rate_Hz", stream.rate_Hz},
                          {"period_s", stream.period_s},
                          {"channels", stream.channels}};
  side.extra["gaps"] = gaps;
  side.extra["samples_missing"] = run.samples_missing;
  side.extra["float_z_mm"] = run.float_z_m * 1e3;
  side.extra["settle_s"] = settings.settle_s;
  side.extra["interrupted"] = run.interrupted;
  side.sdk_version = sdk_version();
  rec.sidecar = side;

  analyze_run(run);
  return run;
}

analysis::Curve curve_of(const Recording& r) {
  analysis::Curve c;
  const auto n = static_cast<Eigen::Index>(r.size());
  c.z_m.resize(n);
  c.i_A.resize(n);
  c.rep.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto u = static_cast<std::size_t>(k);
    c.z_m[k] = r.z_mm[u] * 1e-3;
    c.i_A[k] = r.i_A[u];
    c.rep[k] = r.rep[u];
  }
  return c;
}

void analyze_run(IndentationRun& run) {
  run.analysis.reset();
  run.repetitions.reset();
  run.analysis_reason.clear();
  run.pressure.reset();
  run.pressure_reason.clear();
  if (run.recording.size() == 0) {
    run.analysis_reason = "the recording has no samples of the ramp";
    return;
  }
  const analysis::Curve c = curve_of(run.recording);
  try {
    run.repetitions = analysis::analyze_repetitions(c, run.settings.analysis);
    // one repetition: the pooled analysis is that repetition's (the same samples), so the fits
    // (the costly part: the Sneddon fit solves per sample) are not run twice
    const auto& per = run.repetitions->per_rep;
    if (per.size() == 1 && per.front().chosen) {
      run.analysis = per.front();
    } else {
      run.analysis = analysis::analyze_indentation(c, run.settings.analysis);
    }
  } catch (const ConfigError& e) {
    run.analysis.reset();
    run.repetitions.reset();
    run.analysis_reason = e.what();
    run.pressure_reason = "no indentation analysis: " + run.analysis_reason;
    return;
  }
  if (!run.analysis->contact_z_m) {
    run.pressure_reason = "no contact point for the object force: " + run.analysis->contact_z_m.reason;
    return;
  }
  const Recording& r = run.recording;
  for (const auto& col : r.p_Pa) {
    if (!col) {
      run.pressure_reason = "the recording lacks a pressure column";
      return;
    }
  }
  Eigen::MatrixXd P(static_cast<Eigen::Index>(r.size()), 6);
  for (Eigen::Index ch = 0; ch < 6; ++ch)
    P.col(ch) = Eigen::Map<const Eigen::VectorXd>((*r.p_Pa[static_cast<std::size_t>(ch)]).data(), P.rows());
  try {
    run.pressure = analysis::analyze_pressure(c, P, run.settings.analysis, *run.analysis->contact_z_m.value);
  } catch (const ConfigError& e) {
    run.pressure_reason = e.what();
  }
}

void use_kf_table_of(const Sidecar& side, analysis::IndentationParams& p) {
  if (!side.stroke_origin_z_mm)
    throw ConfigError("the K_f(stroke) table needs the stroke origin, and the sidecar gives none (" +
                      (side.stroke_origin_z_mm_reason.empty() ? std::string("no reason given")
                                                              : side.stroke_origin_z_mm_reason) +
                      "): analyse with the constant K_f");
  const auto t = side.calibration.find("kf_table");
  if (t == side.calibration.end() || !t->is_array() || t->empty())
    throw ConfigError("the K_f(stroke) table: the sidecar's calibration has no kf_table");
  std::vector<double> x, k;
  for (const auto& row : *t) {
    if (!row.is_object() || !row.contains("position_mm") || !row.contains("kf_N_per_A") ||
        !row["position_mm"].is_number() || !row["kf_N_per_A"].is_number())
      throw ConfigError("the K_f(stroke) table: every kf_table row needs position_mm and kf_N_per_A");
    x.push_back(row["position_mm"].get<double>() * 1e-3);
    k.push_back(row["kf_N_per_A"].get<double>());
  }
  p.kf_table_stroke_m = std::move(x);
  p.kf_table_N_per_A = std::move(k);
  p.stroke_origin_z_m = *side.stroke_origin_z_mm * 1e-3;
}

}  // namespace palp
