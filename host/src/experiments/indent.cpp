// SPDX-License-Identifier: Apache-2.0
// The quasi-static indentation (indent.hpp): zero pressures, float the coil, stream the
// device's staircase ramp into a recording, analyse it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "palp/indent.hpp"
#include "palp/pressure_analysis.hpp"
#include "palp/result.hpp"
#include "experiment_common.hpp"

namespace palp {

namespace {

using experiment::wait_device_time;

using experiment::kCountM;

/// Floats the coil at the ramp's start current and lets it settle on the specimen; returns the
/// encoder position it rests at, m.
double float_coil(Probe& probe, const IndentationSettings& s, const std::function<bool()>& cancelled) {
  const ContactEvent event = experiment::float_coil(
      probe, s.start_A, "is the tip pressed against the specimen, or start_A below the float current?");
  wait_device_time(probe, event.t_device_s + s.settle_s, cancelled);
  return probe.status().encoder_counts * kCountM;
}

IndentationRun indent_unguarded(Probe& probe, const IndentationSettings& settings,
                                const IndentProgressFn& progress, const std::function<bool()>& cancelled) {
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
  experiment::release_coil(probe, settings.settle_s, cancelled,
                           [&] { report("releasing the coil", 0, nullptr); });
  if (settings.zero_pressure) {
    report("zeroing pressures", 0, nullptr);
    probe.zero_pressure(settings.zero_pressure_s);
  }
  probe.configure_stream({.rate_Hz = settings.stream_rate_Hz});

  report("floating the coil", 0, nullptr);
  run.float_z_m = float_coil(probe, settings, cancelled);
  experiment::ProgramRecording recorded;
  if (cancelled && cancelled()) {
    recorded.interrupted = true;
    probe.stop();  // the float's contact hold back to 0 A
  } else {
    const double ramp_s = settings.ramp_duration_s();
    recorded = experiment::record_program(
        probe, [&] { probe.load(settings.ramp_program()); probe.start(); }, ramp_s,
        [&](double elapsed_s, const Sample& last) { report("ramp", elapsed_s / ramp_s, &last); }, cancelled);
  }
  run.interrupted = recorded.interrupted;
  run.samples_missing = recorded.samples_missing;
  run.program = recorded.program;
  run.recording = std::move(recorded.recording);
  Recording& rec = run.recording;
  if (rec.size() > 0) {
    report("ramp", 1.0, nullptr);
    rec.rep = split_repetitions_at_current_minima(*rec.i_cmd_A);
  }

  Sidecar side = experiment::base_sidecar(probe, "indentation", recorded);
  side.program = {{"kind", "ramp"},
                  {"parameters", program_json(settings.ramp_program())},
                  {"result",
                   {{"end", proto::enum_name(run.program.end) ? proto::enum_name(run.program.end) : "?"},
                    {"t_device_s", run.program.t_device_s},
                    {"repetitions_done", run.program.repetitions_done}}}};
  side.extra["float_z_mm"] = run.float_z_m * 1e3;
  side.extra["settle_s"] = settings.settle_s;
  rec.sidecar = side;

  analyze_run(run);
  return run;
}

}  // namespace

IndentationRun indent(Probe& probe, const IndentationSettings& settings,
                      const IndentProgressFn& progress, const std::function<bool()>& cancelled) {
  settings.validate();
  return experiment::or_make_safe(probe, [&] { return indent_unguarded(probe, settings, progress, cancelled); });
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
  if (r.i_cmd_A && r.i_cmd_A->size() == r.size())  // the plateaus of the staircase
    c.i_cmd_A = Eigen::Map<const Eigen::VectorXd>(r.i_cmd_A->data(), n);
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
    // (the costly part: the Sneddon fit solves per fit point) are not run twice
    const auto& per = run.repetitions->per_rep;
    if (per.size() == 1 && per.front().chosen) {
      run.analysis = per.front();
    } else {
      run.analysis = analysis::analyze_indentation(c, run.settings.analysis);
    }
  } catch (const DataError& e) {  // a bad setting is no data problem: it propagates
    run.analysis.reset();
    run.repetitions.reset();
    run.analysis_reason = e.what();
    run.pressure_reason = "no indentation analysis: " + run.analysis_reason;
    return;
  }
  try {  // the pressure-force test on the same contact point (pressure_analysis.hpp)
    run.pressure = pressure_analysis_of(run.recording, run.settings.analysis, *run.analysis);
  } catch (const DataError& e) {
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
