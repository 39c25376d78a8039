// SPDX-License-Identifier: Apache-2.0
// palpctl calibrate current-offset|pressure-zero|home|kf: measure, set in RAM, then commit to flash.
// This is the one place the CLI writes the device's flash (zeroing before a measurement with
// `run --zero-*` stays in RAM and is kept in the recording's sidecar instead).
#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>

#include "common.hpp"
#include "option_alias.hpp"
#include "palp/result.hpp"
#include "palp/identification.hpp"
#include "palp/identification_result.hpp"

namespace palpctl {

namespace {
struct CalibrateOptions {
  double seconds = 0.5;
  double home_current_A = -0.3;
  double home_seconds = 1.0;
  bool ram_only = false;
};

int calibrate(const Context& ctx, const std::string& what, const CalibrateOptions& o) {
  auto probe = ctx.connect();
  json j = {{"calibrate", what}};
  if (what == "current-offset") {
    j["current_offset_A"] = f32(static_cast<float>(probe.zero_current_offset(o.seconds)));
  } else if (what == "pressure-zero") {
    json offsets = json::array();
    for (double v : probe.zero_pressure(o.seconds)) offsets.push_back(f32(static_cast<float>(v)));
    j["pressure_offset_Pa"] = offsets;
  } else {
    j["stroke_origin_mm"] = mm_from_counts(probe.home(o.home_current_A, o.home_seconds));
  }
  if (!o.ram_only) probe.commit_calibration();
  j["committed"] = !o.ram_only;
  j["calibration"] = palp::calibration_json(probe.calibration());
  if (ctx.json) {
    print_json(j);
  } else {
    print_text(j);
    std::cout << (o.ram_only ? "set in RAM only (lost at power-off)\n"
                             : "committed to the device's flash\n");
  }
  return kOk;
}

CLI::App* add_one(CLI::App& parent, Context& ctx, const std::string& name,
                  const std::string& help, std::shared_ptr<CalibrateOptions> o) {
  auto* cmd = parent.add_subcommand(name, help);
  cmd->add_flag("--ram-only", o->ram_only,
                "Set the new value in the device's RAM only; do not commit it to flash");
  cmd->callback([&ctx, name, o] { ctx.action = [&ctx, name, o] { return calibrate(ctx, name, *o); }; });
  return cmd;
}
int calibrate_kf(const Context& ctx, const palp::KfCalibrationSettings& settings) {
  settings.validate();
  auto probe = ctx.connect();
  catch_interrupts();  // Ctrl-C stops the staircase (coil at 0 A); nothing is written then
  Progress progress("calibrate kf", 1000, !ctx.json, "permille");
  const palp::KfCalibrationRun run = palp::calibrate_kf(
      probe, settings,
      [&](const palp::IdentifyProgress& p) {
        progress.update(static_cast<std::uint64_t>(p.fraction * 1000));
      },
      [] { return interrupted(); });
  if (run.interrupted) {
    std::cerr << "palpctl: calibrate kf interrupted; nothing written to the device\n";
    return kInterrupted;
  }
  progress.finish(1000);
  const auto& c = run.calibration;
  const json j = palp::kf_calibration_json(run);  // the SDK's result: Python's to_dict() too
  const json& nodes = j["nodes"];
  if (ctx.json) {
    print_json(j);
  } else {
    for (const auto& n : nodes)
      std::printf("stroke %7.3f mm  K_f %.4f +- %.4f N/A\n", n["stroke_mm"].get<double>(),
                  n["kf_N_per_A"].get<double>(), n["kf_N_per_A_se"].get<double>());
    std::printf("%zu levels, residual %.3g N rms; %s\n", run.points.size(), c.residual_rms_N,
                run.committed ? "committed to the device's flash"
                : run.written ? "set in RAM only (lost at power-off)"
                              : "not written to the device");
    if (!c.warning.empty()) std::printf("warning: %s\n", c.warning.c_str());
  }
  return kOk;
}

}  // namespace

void add_calibrate_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand(
      "calibrate", "Measure an offset or the stroke origin, set it and commit it to the "
                   "device's flash (--ram-only to skip the commit)");
  cmd->require_subcommand(1, 1);
  auto o = std::make_shared<CalibrateOptions>();

  // --zero-s as in the recording options (the same zeroing, committed here): --seconds before
  for (auto* zeroing :
       {add_one(*cmd, ctx, "current-offset",
                "With the coil idle (0 A), average the measured current and set the current-sense "
                "offset so it reads 0 A",
                o),
        add_one(*cmd, ctx, "pressure-zero",
                "With the probe unloaded, average each pressure channel and set its offset, Pa", o)})
    add_hidden_alias(*zeroing,
                     zeroing->add_option("--zero-s", o->seconds, "Averaging time, s")
                         ->check(CLI::Range(0.01, 60.0))
                         ->capture_default_str(),
                     "--seconds");
  auto* home = add_one(*cmd, ctx, "home",
                       "Pull the coil against its rear end stop and set the stroke origin there",
                       o);
  home->add_option("--current-A", o->home_current_A,
                   "Holding current, A (negative: toward the rear stop)")
      ->check(CLI::Range(-4.0, -0.01))
      ->capture_default_str();
  home->add_option("--seconds", o->home_seconds, "How long to hold before taking the origin, s")
      ->check(CLI::Range(0.2, 60.0))
      ->capture_default_str();

  auto kf = std::make_shared<palp::KfCalibrationSettings>();
  auto* kfc = cmd->add_subcommand(
      "kf", "Force constant along the stroke, in free air (probe clear of everything): a slow "
            "staircase of currents up and back, each settled level a balance K_f(s) i = k_v (s - "
            "s_rest) + c; K_f(s) piecewise linear over up to 16 nodes, written to the device's "
            "calibration table (needs the stroke origin: calibrate home first)");
  kfc->add_option("--start-A", kf->start_A, "Lowest current, A")->check(CLI::Range(-4.0, 4.0))->capture_default_str();
  kfc->add_option("--stop-A", kf->stop_A, "Highest current, A")->check(CLI::Range(-4.0, 4.0))->capture_default_str();
  kfc->add_option("--step-A", kf->step_A, "Current step, A")->check(CLI::Range(0.0001, 4.0))->capture_default_str();
  kfc->add_option("--dwell-s", kf->dwell_s, "Time on each level (the last half is averaged), s")
      ->check(CLI::Range(0.05, 100.0))->capture_default_str();
  kfc->add_option("--nodes", kf->max_nodes, "Most table nodes (the block holds 16)")
      ->check(CLI::Range(2, 16))->capture_default_str();
  auto kv_mm = std::make_shared<double>(kf->k_v_N_per_m * 1e-3);
  kfc->add_option("--kv-N-per-mm", *kv_mm, "Return springs k_v, N/mm (known: the balance needs it)")
      ->check(kPositive)->capture_default_str();
  kfc->add_option("--rate-Hz", kf->stream_rate_Hz, "Stream rate, Hz")->check(CLI::Range(1.0, 1000.0))->capture_default_str();
  auto anchor = std::make_shared<std::pair<double, double>>(kf->anchor->stroke_m * 1e3, kf->anchor->kf_N_per_A);
  auto* anchor_mm = kfc->add_option("--anchor-mm", anchor->first,
                                    "The balance fixes K_f only up to a constant's share: anchor it at this "
                                    "stroke position (from the stroke origin), mm")
                        ->check(kNonNegative)->capture_default_str();
  auto* anchor_kf = kfc->add_option("--anchor-kf-N-per-A", anchor->second,
                                    "... to this known K_f there, N/A (the paper: 2.918 at 24 mm of travel)")
                        ->check(kPositive)->capture_default_str();
  auto no_anchor = std::make_shared<bool>(false);
  kfc->add_flag("--no-anchor", *no_anchor, "Fit without an anchor (the result warns when c, and with it K_f, is poorly determined)")
      ->excludes(anchor_mm)->excludes(anchor_kf);
  auto ram_only = std::make_shared<bool>(false);
  kfc->add_flag("--ram-only", *ram_only, "Set the table in the device's RAM only; do not commit it to flash");
  kfc->callback([&ctx, kf, kv_mm, ram_only, anchor, no_anchor] {
    kf->k_v_N_per_m = *kv_mm * 1e3;
    if (*no_anchor) kf->anchor.reset();
    else kf->anchor = palp::analysis::KfAnchor{anchor->first * 1e-3, anchor->second};
    kf->write = true;
    kf->commit = !*ram_only;
    ctx.action = [&ctx, kf] { return calibrate_kf(ctx, *kf); };
  });
}

}  // namespace palpctl
