// SPDX-License-Identifier: Apache-2.0
// palpctl run ramp|sine|sweep|hold: run a device program while streaming, into a recording.
// The options mirror the protocol's Load* messages (protocol/include/palp/protocol/catalogue.hpp)
// with the same defaults, in lab units (mm instead of encoder counts).
#include <memory>

#include "acquire.hpp"

namespace palpctl {

namespace {

struct RunOptions {
  AcquireOptions acq;
  palp::HoldProgram hold;
  palp::RampProgram ramp;
  double displacement_limit_mm = 0;
  bool no_unload = false;
  palp::SineProgram sine;
  palp::SweepProgram sweep;
};

CLI::App* add_program(CLI::App& run, Context& ctx, std::shared_ptr<RunOptions> o,
                      const std::string& name, const std::string& help,
                      std::function<palp::RecordedProgram(const RunOptions&)> spec) {
  auto* cmd = run.add_subcommand(name, help);
  cmd->callback([&ctx, o, spec] {
    ctx.action = [&ctx, o, spec] { return acquire(ctx, o->acq, spec(*o)); };
  });
  return cmd;
}

template <class T>
CLI::Option* opt(CLI::App* cmd, const std::string& name, T& value, const std::string& help) {
  return cmd->add_option(name, value, help)->capture_default_str();
}

}  // namespace

void add_run_command(CLI::App& app, Context& ctx) {
  auto* run = app.add_subcommand(
      "run", "Run a program on the device while streaming, and write a recording (CSV + JSON "
             "sidecar with the program, device info, calibration and zeroing)");
  run->require_subcommand(1, 1);
  auto o = std::make_shared<RunOptions>();

  // --- hold ---
  auto* hold = add_program(*run, ctx, o, "hold", "Hold a current for a time",
                           [](const RunOptions& r) {
    auto h = r.hold;
    h.duration_s = static_cast<float>(r.acq.seconds);  // the program ends itself
    return h;
  });
  opt(hold, "--current-A", o->hold.current_A, "Held current, A")->check(CLI::Range(-4.0, 4.0));
  hold->add_option("--seconds", o->acq.seconds, "How long, s")
      ->required()
      ->check(CLI::Range(0.001, 1e6));

  // --- ramp ---
  auto* ramp = add_program(*run, ctx, o, "ramp",
                           "Staircase ramp: from --start-A to --stop-A by --step-A, --dwell-s on "
                           "each step, symmetric unload, --reps times",
                           [](const RunOptions& r) {
    auto m = r.ramp;
    m.unload = r.no_unload ? 0 : 1;
    m.displacement_limit_counts =
        static_cast<std::uint32_t>(counts_from_mm(r.displacement_limit_mm));
    return m;
  });
  opt(ramp, "--start-A", o->ramp.start_A, "First step's current, A")->check(CLI::Range(-4.0, 4.0));
  opt(ramp, "--stop-A", o->ramp.stop_A, "Top step's current, A")->check(CLI::Range(-4.0, 4.0));
  opt(ramp, "--step-A", o->ramp.step_A, "Increment between steps, A")
      ->check(CLI::Range(0.0001, 4.0));
  opt(ramp, "--dwell-s", o->ramp.dwell_s, "Time on each step, s")->check(CLI::Range(0.0001, 100.0));
  opt(ramp, "--reps", o->ramp.repetitions, "Load/unload cycles")->check(CLI::Range(1, 1000));
  ramp->add_flag("--no-unload", o->no_unload, "Climb only; each repetition starts again at "
                                              "--start-A");
  opt(ramp, "--displacement-limit-mm", o->displacement_limit_mm,
      "Turn round early once the tip moved this far from the ramp's start, mm (0: no limit)")
      ->check(CLI::Range(0.0, 100.0));
  ramp->add_option("--seconds", o->acq.seconds, "Stop the program after this long, s (0: at its "
                                                "end)")
      ->check(kNonNegative);

  // --- sine ---
  auto* sine = add_program(*run, ctx, o, "sine", "Sine about an offset current",
                           [](const RunOptions& r) {
    return r.sine;
  });
  o->sine.cycles = 10;  // the catalogue's 0 runs until stopped; a recording wants an end
  opt(sine, "--offset-A", o->sine.offset_A, "Mean current, A")->check(CLI::Range(-4.0, 4.0));
  opt(sine, "--amplitude-A", o->sine.amplitude_A, "Peak deviation from the offset, A")
      ->check(CLI::Range(0.0, 4.0));
  opt(sine, "--frequency-Hz", o->sine.frequency_Hz, "Frequency, Hz")
      ->check(CLI::Range(0.01, 2000.0));
  opt(sine, "--cycles", o->sine.cycles, "Cycles to run (0: until --seconds)");
  sine->add_option("--seconds", o->acq.seconds,
                   "Stop the program after this long, s (0: after --cycles)")
      ->check(kNonNegative);

  // --- sweep ---
  auto* sweep = add_program(*run, ctx, o, "sweep",
                            "Stepped-sine sweep from --start-Hz to --stop-Hz by --step-Hz",
                            [](const RunOptions& r) {
    return r.sweep;
  });
  opt(sweep, "--offset-A", o->sweep.offset_A, "Mean current, A")->check(CLI::Range(-4.0, 4.0));
  opt(sweep, "--amplitude-A", o->sweep.amplitude_A, "Peak deviation from the offset, A")
      ->check(CLI::Range(0.0, 4.0));
  opt(sweep, "--start-Hz", o->sweep.start_Hz, "First line, Hz")->check(CLI::Range(0.01, 2000.0));
  opt(sweep, "--stop-Hz", o->sweep.stop_Hz, "Last line, Hz (inclusive when on the step grid)")
      ->check(CLI::Range(0.01, 2000.0));
  opt(sweep, "--step-Hz", o->sweep.step_Hz, "Line spacing, Hz")->check(CLI::Range(0.001, 1000.0));
  opt(sweep, "--settle-cycles", o->sweep.settle_cycles, "Cycles discarded at each line")
      ->check(CLI::Range(0, 10000));
  opt(sweep, "--settle-min-s", o->sweep.settle_min_s, "Settle at least this long per line, s")
      ->check(CLI::Range(0.0, 100.0));
  opt(sweep, "--measure-cycles", o->sweep.measure_cycles, "Cycles measured at each line")
      ->check(CLI::Range(1, 10000));
  sweep->add_option("--seconds", o->acq.seconds, "Stop the program after this long, s (0: at "
                                                 "its end)")
      ->check(kNonNegative);

  // the recording's options after the program's own on every --help page
  for (auto* cmd : {hold, ramp, sine, sweep}) add_acquire_options(*cmd, o->acq);
}

}  // namespace palpctl
