// SPDX-License-Identifier: Apache-2.0
// palpctl freeair and palpctl sweep: the probe's frequency response at its current position
// (palp::identify), written as a result directory (palp::write_identification_result) and the
// analysis printed: in free air the instrument's m_v and b_v; in contact the fit and, with
// --static, the paper's decomposition.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "palp/identification_result.hpp"
#include "palp/result.hpp"
#include "sweep_options.hpp"

namespace palpctl {

namespace {

int sweep(const Context& ctx, const SweepCli& o, bool free_air) {
  const char* name = free_air ? "freeair" : "sweep";
  const palp::IdentificationSettings settings = settings_of(o);
  settings.validate();
  const std::filesystem::path dir(o.out_dir);
  if (!o.out_dir.empty() && !o.overwrite && std::filesystem::exists(dir))
    throw palp::ConfigError(o.out_dir + " already exists; choose another --out-dir, or pass "
                            "--overwrite to replace it");
  if (!o.out_dir.empty()) palp::check_replaceable(dir);  // --overwrite replaces only palp's own
  auto probe = ctx.connect();
  const std::uint32_t rate = probe.params().control_rate_Hz;
  settings.check_excitation(rate);  // before anything moves
  catch_interrupts();
  const double device_s = settings.device_time_s(rate);
  if (!ctx.json)
    std::cerr << name << ": " << palp::sweep_method_name(settings.method) << ", " << std::lround(device_s)
              << " s of device time\n";
  Progress progress(name, static_cast<std::uint64_t>(std::llround(device_s)), !ctx.json, "s of device time");
  std::string phase;
  std::uint64_t done_s = 0;
  const palp::IdentificationRun run = palp::identify(
      probe, settings,
      [&](const palp::IdentifyProgress& p) {
        const bool exciting = p.phase == "stepped sine" || p.phase == "multisine";
        if (exciting) {
          done_s = static_cast<std::uint64_t>(std::llround(p.fraction * device_s));
          progress.update(done_s);
        } else if (p.phase != phase) {
          if (p.phase == "analysing") progress.finish(done_s);
          if (!ctx.json) std::cerr << name << ": " << p.phase << '\n';
        }
        phase = p.phase;
      },
      [] { return interrupted(); });
  if (phase != "analysing") progress.finish(done_s);
  if (run.recording.size() == 0) {
    std::cerr << "palpctl: " << name << (run.interrupted ? " interrupted before the excitation; nothing written\n"
                                                         : ": the excitation gave no samples\n");
    return run.interrupted ? kInterrupted : kRuntime;
  }
  json analysis = nullptr;
  if (run.frf && run.fit) analysis = analysis_json(o, *run.frf, *run.fit, settings.bias_A, free_air);
  json out = analysis.is_null() ? json{{"analysis_reason", run.analysis_reason}} : analysis;
  if (!o.out_dir.empty()) {
    const auto written = palp::write_identification_result(
        dir, run, analysis, o.overwrite ? palp::Overwrite::yes : palp::Overwrite::no);
    out["result_dir"] = written.string();
  }
  const char* end = palp::proto::enum_name(run.program.end);
  out["run"] = {{"end", run.interrupted ? "interrupted" : end ? end : "unknown"},
                {"samples", run.recording.size()},
                {"samples_missing", run.samples_missing}};
  if (ctx.json) {
    print_json(out);
  } else {
    if (out.contains("result_dir")) std::cout << "wrote " << out["result_dir"].get<std::string>() << '\n';
    if (analysis.is_null()) std::cout << "no analysis: " << run.analysis_reason << '\n';
    else print_analysis(analysis);
  }
  return run.interrupted ? kInterrupted : kOk;
}

CLI::App* add_one(CLI::App& app, Context& ctx, const char* name, const char* help, bool free_air) {
  const auto preset = palp::IdentificationSettings::preset(free_air ? palp::IdentificationPreset::free_air
                                                                    : palp::IdentificationPreset::contact_multisine);
  auto o = std::make_shared<SweepCli>(SweepCli::of(preset));
  auto* cmd = app.add_subcommand(name, help);
  add_program_options(cmd, *o);
  if (!free_air) add_analysis_options(cmd, *o);
  cmd->add_option("--out-dir", o->out_dir,
                  "Write a result directory: result.json, sweep.csv + sweep.json (the recording), "
                  "frf.csv (the measured response, readable by analyze sweep)");
  cmd->add_flag("--overwrite", o->overwrite, "Replace an existing result directory");
  cmd->callback([&ctx, o, free_air] { ctx.action = [&ctx, o, free_air] { return sweep(ctx, *o, free_air); }; });
  return cmd;
}

}  // namespace

void add_sweep_commands(CLI::App& app, Context& ctx) {
  add_one(app, ctx, "freeair",
          "Free-air identification with the probe clear of everything: bias at the float current, "
          "a small multisine (or stepped sine) over 1-10 Hz; fits omega_n and zeta and gives the "
          "instrument's m_v and b_v with the spring's k_v. Settings whose predicted excursion "
          "exceeds --max-excursion-mm are refused before anything moves",
          true);
  add_one(app, ctx, "sweep",
          "Contact identification at a bias current: the paper's stepped sine (--method stepped, "
          "~665 s) or a multisine of the same peak (60 s); the second-order fit and, with --static, "
          "m_eff and b_o. The contact must hold: bias - peak > I_c is checked first",
          false);
}

}  // namespace palpctl
