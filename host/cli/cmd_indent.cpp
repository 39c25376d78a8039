// SPDX-License-Identifier: Apache-2.0
// palpctl indent: the quasi-static indentation at the probe's current position (palp::indent),
// written as a result directory (palp::write_result), its analysed summary printed.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "common.hpp"
#include "palp/indent.hpp"
#include "palp/result.hpp"

namespace palpctl {

namespace {

struct IndentCli {
  std::string preset = "1d";
  std::string out_dir;
  bool overwrite = false;
  double start_A = 0.5, stop_A = 3.0, step_A = 0.01;
  std::optional<double> dwell_s;
  std::optional<int> reps;
  bool no_unload = false;
  double displacement_limit_mm = 5.0;
  double rate_Hz = 1000;
  bool no_zero_pressure = false;
  double settle_s = 1.2;
  // analysis, lab units (the paper's values)
  double kf_N_per_A = 2.918, ic_A = 0.5, kv_N_per_mm = 0.0439, tip_radius_mm = 2.5, poisson = 0.5;
  double bias_current_A = 1.0;
  std::optional<double> bias_force_N, thickness_mm;
  bool unbonded = false;
};

palp::IndentationSettings settings_of(const IndentCli& o) {
  auto s = palp::IndentationSettings::preset(o.preset == "2d" ? palp::IndentationPreset::two_d
                                                              : palp::IndentationPreset::one_d);
  s.start_A = o.start_A;
  s.stop_A = o.stop_A;
  s.step_A = o.step_A;
  if (o.dwell_s) s.dwell_s = *o.dwell_s;
  if (o.reps) s.repetitions = *o.reps;
  s.unload = !o.no_unload;
  s.displacement_limit_m = o.displacement_limit_mm * 1e-3;
  s.stream_rate_Hz = o.rate_Hz;
  s.zero_pressure = !o.no_zero_pressure;
  s.settle_s = o.settle_s;
  auto& a = s.analysis;
  a.force_constant_N_per_A = o.kf_N_per_A;
  a.contact_current_A = o.ic_A;
  a.spring_N_per_m = o.kv_N_per_mm * 1e3;
  a.tip_radius_m = o.tip_radius_mm * 1e-3;
  a.poisson = o.poisson;
  a.bias_current_A = o.bias_force_N ? o.ic_A + *o.bias_force_N / o.kf_N_per_A : o.bias_current_A;
  if (o.thickness_mm)
    a.thickness = palp::analysis::Thickness{
        *o.thickness_mm * 1e-3, o.unbonded ? palp::analysis::Bonding::unbonded : palp::analysis::Bonding::bonded};
  return s;
}

/// The human form: the headline numbers, each with its unit in its name.
void print_summary(const json& j) {
  static const char* keys[] = {"model_by_aic",        "contact_point_mm",     "delta0_mm",
                               "delta0_mm_sd",        "k_tangent_N_per_mm",   "k_tangent_N_per_mm_sd",
                               "k_fd_N_per_mm",       "k_fd_N_per_mm_sd",     "k_ls_window_N_per_mm",
                               "k_fd_paper_N_per_mm", "k_linear_N_per_mm",    "r2_linear",
                               "E_star_hertz_Pa",     "r2_hertz",             "E_star_sneddon_Pa",
                               "r2_sneddon",          "k_at_depth_N_per_mm"};
  json out = json::object();
  for (const char* k : keys) {
    if (!j.contains(k)) continue;
    out[k] = j[k];
    if (j.contains(std::string(k) + "_reason")) out[std::string(k) + "_reason"] = j[std::string(k) + "_reason"];
  }
  print_text(out);
}

int indent(const Context& ctx, const IndentCli& o) {
  const palp::IndentationSettings settings = settings_of(o);
  settings.validate();
  const std::filesystem::path dir(o.out_dir);
  if (!o.overwrite && std::filesystem::exists(dir))
    throw palp::ConfigError(o.out_dir + " already exists; choose another --out-dir, or pass "
                            "--overwrite to replace it");
  palp::check_replaceable(dir);  // --overwrite replaces only a result directory palp wrote
  auto probe = ctx.connect();
  catch_interrupts();  // Ctrl-C stops the ramp and keeps what was recorded
  const double rate = settings.stream_rate_Hz;
  const auto expected = static_cast<std::uint64_t>(std::llround(settings.ramp_duration_s() * rate));
  Progress progress("indent", expected, !ctx.json);
  std::string phase;
  const palp::IndentationRun run = palp::indent(
      probe, settings,
      [&](const palp::IndentProgress& p) {
        if (!ctx.json && p.phase != "ramp" && p.phase != phase) std::cerr << "indent: " << p.phase << '\n';
        phase = p.phase;
        if (p.phase == "ramp") progress.update(static_cast<std::uint64_t>(p.fraction * static_cast<double>(expected)));
      },
      [] { return interrupted(); });
  progress.finish(static_cast<std::uint64_t>(
      std::llround(run.recording.size() > 0 ? static_cast<double>(expected) : 0.0)));
  if (run.recording.size() == 0 && run.interrupted) {
    std::cerr << "palpctl: indent interrupted before the ramp started; nothing written\n";
    return kInterrupted;
  }
  if (run.recording.size() == 0) throw palp::Error("indent: the ramp gave no samples");
  const auto written = palp::write_result(dir, run, o.overwrite ? palp::Overwrite::yes : palp::Overwrite::no);

  json summary = run.analysis ? palp::indentation_summary_json(*run.analysis,
                                                               run.repetitions ? &*run.repetitions : nullptr,
                                                               settings.analysis)
                              : json{{"params", palp::indentation_params_json(settings.analysis)}};
  if (!run.analysis) summary["analysis_reason"] = run.analysis_reason;
  const char* end = palp::proto::enum_name(run.program.end);
  if (run.pressure) {
    summary["pressure"] = palp::pressure_summary_json(*run.pressure);
  } else {
    summary["pressure"] = nullptr;
    summary["pressure_reason"] = run.pressure_reason;
  }
  summary["result_dir"] = written.string();
  summary["run"] = {{"end", run.interrupted ? "interrupted" : end ? end : "unknown"},
                    {"samples", run.recording.size()},
                    {"samples_missing", run.samples_missing},
                    {"repetitions_done", run.program.repetitions_done}};
  if (ctx.json) {
    print_json(summary);
  } else {
    std::cout << "wrote " << written.string() << " (" << run.recording.size() << " samples, "
              << run.samples_missing << " missing)\n";
    if (!run.analysis) std::cout << "no analysis: " << run.analysis_reason << '\n';
    else print_summary(summary);
  }
  return run.interrupted ? kInterrupted : kOk;
}

}  // namespace

void add_indent_command(CLI::App& app, Context& ctx) {
  auto o = std::make_shared<IndentCli>();
  auto* cmd = app.add_subcommand(
      "indent", "Quasi-static indentation at the probe's current position: zero the pressures, "
                "float the coil, staircase ramp with symmetric unload (stream <= 1 kHz), analyse; "
                "writes a result directory (docs/result-format.md) and prints the summary");
  cmd->add_option("--preset", o->preset, "1d: every 100 ms, 5 reps; 2d: every 25 ms, 3 reps (paper)")
      ->check(CLI::IsMember({"1d", "2d"}))
      ->capture_default_str();
  cmd->add_option("--out-dir", o->out_dir, "The result directory to write (appears whole or not at all)")
      ->required();
  cmd->add_flag("--overwrite", o->overwrite, "Replace an existing result directory");
  cmd->add_option("--start-A", o->start_A, "First step's current (the coil floats at it first), A")
      ->check(CLI::Range(-4.0, 4.0))->capture_default_str();
  cmd->add_option("--stop-A", o->stop_A, "Top step's current, A")->check(CLI::Range(-4.0, 4.0))->capture_default_str();
  cmd->add_option("--step-A", o->step_A, "Increment between steps, A")
      ->check(CLI::Range(0.0001, 4.0))->capture_default_str();
  cmd->add_option("--dwell-s", o->dwell_s, "Time on each step, s (default: the preset's, 0.1 or 0.025)")
      ->check(CLI::Range(0.0001, 100.0));
  cmd->add_option("--reps", o->reps, "Load/unload cycles (default: the preset's, 5 or 3)")
      ->check(CLI::Range(1, 1000));
  cmd->add_flag("--no-unload", o->no_unload, "Climb only (no symmetric unload)");
  cmd->add_option("--displacement-limit-mm", o->displacement_limit_mm,
                  "Turn round early once the tip moved this far from the ramp's start, mm (0: none)")
      ->check(CLI::Range(0.0, 100.0))->capture_default_str();
  cmd->add_option("--rate-Hz", o->rate_Hz, "Stream rate, Hz (at most 1000)")
      ->check(CLI::Range(1.0, 1000.0))->capture_default_str();
  cmd->add_flag("--no-zero-pressure", o->no_zero_pressure, "Do not zero the pressure channels first");
  cmd->add_option("--settle-s", o->settle_s, "Device time the floating coil settles before the ramp, s")
      ->check(CLI::Range(0.0, 60.0))->capture_default_str();
  cmd->add_option("--kf-N-per-A", o->kf_N_per_A, "Analysis: force constant K_f, N/A")
      ->check(kPositive)->capture_default_str();
  cmd->add_option("--ic-A", o->ic_A, "Analysis: contact threshold current I_c, A")->capture_default_str();
  cmd->add_option("--kv-N-per-mm", o->kv_N_per_mm, "Analysis: return-spring stiffness k_v, N/mm")
      ->check(kNonNegative)->capture_default_str();
  cmd->add_option("--tip-radius-mm", o->tip_radius_mm, "Analysis: tip radius R, mm")
      ->check(kPositive)->capture_default_str();
  cmd->add_option("--poisson", o->poisson, "Analysis: the specimen's Poisson ratio")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  auto* bias_i = cmd->add_option("--bias-current-A", o->bias_current_A,
                                 "Analysis: operating point I_0, A (F_0 = K_f (I_0 - I_c))")
                     ->capture_default_str();
  cmd->add_option("--bias-force-N", o->bias_force_N, "Analysis: operating point F_0, N (instead of --bias-current-A)")
      ->check(kPositive)
      ->excludes(bias_i);
  auto* thickness = cmd->add_option("--thickness-mm", o->thickness_mm,
                                    "Analysis: layer thickness for the finite-thickness correction, mm")
                        ->check(kPositive);
  cmd->add_flag("--unbonded", o->unbonded, "Analysis: the layer slides on its base (default: bonded)")
      ->needs(thickness);
  cmd->callback([&ctx, o] { ctx.action = [&ctx, o] { return indent(ctx, *o); }; });
}

}  // namespace palpctl
