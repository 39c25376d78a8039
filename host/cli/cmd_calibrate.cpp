// palpctl calibrate current-offset|pressure-zero|home: measure, set in RAM, then commit to flash.
// This is the one place the CLI writes the device's flash (zeroing before a measurement with
// `run --zero-*` stays in RAM and is kept in the recording's sidecar instead).
#include <iostream>

#include "common.hpp"

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
  j["calibration"] = to_json(probe.calibration());
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
}  // namespace

void add_calibrate_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand(
      "calibrate", "Measure an offset or the stroke origin, set it and commit it to the "
                   "device's flash (--ram-only to skip the commit)");
  cmd->require_subcommand(1, 1);
  auto o = std::make_shared<CalibrateOptions>();

  add_one(*cmd, ctx, "current-offset",
          "With the coil idle (0 A), average the measured current and set the current-sense "
          "offset so it reads 0 A",
          o)
      ->add_option("--seconds", o->seconds, "Averaging time, s")
      ->check(CLI::Range(0.01, 60.0))
      ->capture_default_str();
  add_one(*cmd, ctx, "pressure-zero",
          "With the probe unloaded, average each pressure channel and set its offset, Pa", o)
      ->add_option("--seconds", o->seconds, "Averaging time, s")
      ->check(CLI::Range(0.01, 60.0))
      ->capture_default_str();
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
}

}  // namespace palpctl
