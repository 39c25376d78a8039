// SPDX-License-Identifier: Apache-2.0
// Force-constant calibration in free air (identification.hpp): a slow staircase both ways, the
// absolute balance fitted for K_f(stroke) (kf_calibration.hpp), the table written to the
// device's calibration block.
#include <cmath>
#include <string>

#include "experiment_common.hpp"
#include "finite.hpp"
#include "palp/error.hpp"
#include "palp/identification.hpp"
#include "palp/identification_result.hpp"
#include "palp/protocol/program_schedule.hpp"
#include "palp/result.hpp"

namespace palp {

namespace {

void require_kf(bool ok, const std::string& what) {
  if (!ok) throw ConfigError("K_f calibration settings: " + what);
}

proto::LoadRamp ramp_of(const KfCalibrationSettings& s) {
  proto::LoadRamp m;
  m.start_A = static_cast<float>(s.start_A);
  m.stop_A = static_cast<float>(s.stop_A);
  m.step_A = static_cast<float>(s.step_A);
  m.dwell_s = static_cast<float>(s.dwell_s);
  m.repetitions = 1;
  m.unload = 1;
  m.displacement_limit_counts = 0;
  return m;
}


}  // namespace

void KfCalibrationSettings::validate() const {
  experiment::require_finite(
      "K_f calibration settings",
      {{"start_A", start_A}, {"stop_A", stop_A}, {"step_A", step_A}, {"dwell_s", dwell_s},
       {"settled_fraction", settled_fraction}, {"k_v_N_per_m", k_v_N_per_m},
       {"stream_rate_Hz", stream_rate_Hz}, {"anchor.stroke_m", anchor ? anchor->stroke_m : 0.0},
       {"anchor.kf_N_per_A", anchor ? anchor->kf_N_per_A : 0.0}});
  auto finite = [](double v) { return std::isfinite(v); };
  require_kf(finite(start_A) && start_A > 0 && start_A <= 4,
          "start_A must lie in (0, 4] A (the coil must float off its rear stop)");
  require_kf(finite(stop_A) && stop_A > start_A && stop_A <= 4, "stop_A must lie above start_A, at most 4 A");
  require_kf(finite(step_A) && step_A >= 1e-4 && step_A <= stop_A - start_A,
          "step_A must lie in 0.0001 A .. stop_A - start_A");
  require_kf(finite(dwell_s) && dwell_s >= 0.05 && dwell_s <= 100, "dwell_s must lie in 0.05..100 s");
  require_kf(finite(settled_fraction) && settled_fraction > 0 && settled_fraction <= 1,
          "settled_fraction must lie in (0, 1]");
  require_kf(max_nodes >= 2 && max_nodes <= 16, "max_nodes must lie in 2..16 (the calibration block holds 16)");
  require_kf(finite(k_v_N_per_m) && k_v_N_per_m > 0, "k_v_N_per_m must be positive");
  require_kf(finite(stream_rate_Hz) && stream_rate_Hz > 0 && stream_rate_Hz <= 1000,
          "stream_rate_Hz must lie in (0, 1000] Hz");
  require_kf(!anchor || (finite(anchor->stroke_m) && finite(anchor->kf_N_per_A) && anchor->kf_N_per_A > 0),
          "anchor must have a finite stroke and a positive K_f");
  require_kf(!commit || write, "commit needs write (only the table written to RAM can be committed)");
}

namespace {
KfCalibrationRun calibrate_kf_unguarded(Probe& probe, const KfCalibrationSettings& settings,
                                        const IdentifyProgressFn& progress,
                                        const std::function<bool()>& cancelled) {
  KfCalibrationRun run;
  run.settings = settings;
  auto report = [&](const char* phase, double fraction) {
    if (progress) progress(IdentifyProgress{phase, std::min(1.0, std::max(0.0, fraction)), 0});
  };
  const DeviceInfo device = probe.info();
  const auto rate = static_cast<std::uint32_t>(std::lround(device.control_rate_Hz));
  experiment::release_coil(probe, 1.0, cancelled, [&] { report("releasing the coil", 0); });
  // the table's positions are from the stroke origin: home first when it is not known
  if (probe.calibration().stroke_origin_valid == 0) {
    report("homing", 0);
    probe.home();
  }
  const double origin_z_m = probe.calibration().stroke_origin_counts * 1e-6;
  probe.configure_stream({.rate_Hz = settings.stream_rate_Hz});

  const proto::LoadRamp ramp = ramp_of(settings);
  const double duration_s =
      static_cast<double>(proto::ramp_timing(ramp, rate).total_ticks) / static_cast<double>(rate);
  experiment::ProgramRecording rec = experiment::record_program(
      probe,
      [&] {
        probe.load(ramp);
        probe.start();
      },
      duration_s, [&](double elapsed_s, const Sample&) { report("staircase", elapsed_s / duration_s); },
      cancelled);
  run.recording = std::move(rec.recording);
  if (rec.interrupted) {  // a partial staircase: nothing fitted, nothing written
    run.interrupted = true;
    run.recording.sidecar = experiment::base_sidecar(probe, "kf_calibration", rec);
    return run;
  }
  report("analysing", 1.0);
  if (run.recording.size() == 0) throw ConfigError("K_f calibration: the staircase recorded no samples");

  run.points = analysis::kf_static_points(run.recording, ramp, rate, origin_z_m, settings.settled_fraction);
  const std::vector<double> nodes = analysis::kf_nodes_for(run.points, settings.max_nodes);
  run.calibration = settings.anchor
                        ? analysis::fit_kf_table(run.points, settings.k_v_N_per_m, nodes, *settings.anchor)
                        : analysis::fit_kf_table(run.points, settings.k_v_N_per_m, nodes);

  // the sidecar keeps the calibration in force while the staircase ran
  Sidecar side = experiment::base_sidecar(probe, "kf_calibration", rec);
  if (settings.write) {
    Calibration cal = probe.calibration();
    cal.kf_position_counts = {};
    cal.kf_N_per_A = {};
    for (std::size_t k = 0; k < run.calibration.node_stroke_m.size(); ++k) {
      cal.kf_position_counts.push_back(
          static_cast<std::int32_t>(std::lround(run.calibration.node_stroke_m[k] * 1e6)));
      cal.kf_N_per_A.push_back(static_cast<float>(run.calibration.kf_N_per_A[k]));
    }
    probe.set_calibration(cal);
    run.written = true;
    if (settings.commit) {
      probe.commit_calibration();
      run.committed = true;
    }
  }

  side.program = {{"kind", "ramp"},
                  {"parameters", program_json(ramp)},
                  {"result",
                   {{"end", proto::enum_name(rec.program.end) ? proto::enum_name(rec.program.end) : "?"},
                    {"t_device_s", rec.program.t_device_s},
                    {"repetitions_done", rec.program.repetitions_done}}}};
  side.extra["control_rate_Hz"] = rate;
  side.extra["kf_calibration"] = {{"settled_fraction", settings.settled_fraction},
                                  {"max_nodes", settings.max_nodes},
                                  {"k_v_N_per_mm", settings.k_v_N_per_m * 1e-3},
                                  {"anchor", settings.anchor ? nlohmann::json{{"position_mm", settings.anchor->stroke_m * 1e3},
                                                                              {"kf_N_per_A", settings.anchor->kf_N_per_A}}
                                                             : nlohmann::json(nullptr)},
                                  {"warning", run.calibration.warning},
                                  {"written", run.written},
                                  {"committed", run.committed}};
  run.recording.sidecar = side;
  return run;
}
}  // namespace

KfCalibrationRun calibrate_kf(Probe& probe, const KfCalibrationSettings& settings,
                              const IdentifyProgressFn& progress,
                              const std::function<bool()>& cancelled) {
  settings.validate();
  return experiment::or_make_safe(
      probe, [&] { return calibrate_kf_unguarded(probe, settings, progress, cancelled); });
}

nlohmann::json kf_calibration_json(const KfCalibrationRun& run) {
  const analysis::KfCalibration& c = run.calibration;
  nlohmann::json nodes = nlohmann::json::array();
  for (std::size_t k = 0; k < c.node_stroke_m.size(); ++k)
    nodes.push_back({{"stroke_mm", c.node_stroke_m[k] * 1e3},
                     {"kf_N_per_A", c.kf_N_per_A[k]},
                     {"kf_N_per_A_se", c.kf_se_N_per_A[k]}});
  const auto& anchor = run.settings.anchor;
  return {{"calibrate", "kf"},
          {"balance", "K_f(s) i = k_v (s - s_rest) + c, least squares over the settled levels"},
          {"kv_N_per_mm", c.k_v_N_per_m / 1e3},
          {"levels", run.points.size()},
          {"nodes", nodes},
          {"c_N", c.c_N},
          {"c_N_se", c.c_se_N},
          {"residual_rms_N", c.residual_rms_N},
          {"anchor", anchor ? nlohmann::json{{"stroke_mm", anchor->stroke_m * 1e3},
                                             {"kf_N_per_A", anchor->kf_N_per_A}}
                            : nlohmann::json(nullptr)},
          {"warning", c.warning},
          {"written", run.written},
          {"committed", run.committed}};
}

}  // namespace palp
