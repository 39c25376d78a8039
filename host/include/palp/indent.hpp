// SPDX-License-Identifier: Apache-2.0
// Experiments (issue 6): what a lab program runs at one probe position and gets a result from.
//
//   palp::Probe probe("sim://127.0.0.1:7070");
//   palp::IndentationSettings s = palp::IndentationSettings::preset(palp::IndentationPreset::one_d);
//   palp::IndentationRun run = palp::indent(probe, s, [](const palp::IndentProgress& p) {
//     std::fprintf(stderr, "\r%s %3.0f%%", p.phase.c_str(), 100 * p.fraction);
//   });
//   palp::write_result("results/solid-p3", run);        // result.hpp: the result directory
//   if (run.analysis) use(run.analysis->delta0_m);
//
// Quasi-static indentation at the current position (paper §IV-A, §V-A), in this order:
//   0. when the coil carries a current (a program running, or a contact watch that ended holding
//      its current, as the toucher leaves it), stop it and wait settle_s: the coil rests at 0 A;
//   1. zero the pressure channels (device RAM, kept in the sidecar), the coil at 0 A and so
//      unloaded: before every indentation, as the paper does;
//   2. float the coil at start_A: a contact watch at start_A lets the coil leave its rear stop
//      and keeps that current on when it fires; then settle_s of device time, so the ramp starts
//      with the tip resting on the specimen (the caller, or the robot, placed the probe so that
//      the floating tip touches: the paper's protocol starts in contact, with no baseline);
//   3. the device's staircase ramp (RampProgram): start_A → stop_A by step_A every dwell_s,
//      symmetric unload, `repetitions` times, turned round early once the coil moved
//      displacement_limit_m from where the ramp started (the firmware's own check, every tick);
//   4. the stream (every channel, pressures included, at stream_rate_Hz ≤ 1 kHz) is recorded
//      while the ramp runs; only samples the ramp drives (program_running set) are kept. The
//      repetition of each sample comes from split_repetitions_at_current_minima over the
//      commanded current (exact for the symmetric staircase);
//   5. the coil goes back to 0 A, and the recording is analysed with analyze_indentation (all
//      repetitions pooled: the model fits, AIC, contact point) and analyze_repetitions (each
//      repetition alone: mean and s.d. of the descriptors), with the caller's IndentationParams.
// The pressure–force test is this run: its recording carries p1_Pa..p6_Pa, and run.pressure
// regresses each channel on the object force (analyze_pressure).
//
// Errors: bad settings are ConfigError before the device does anything; a coil that does not
// float (pressed against something, or start_A below the float current) is a TimeoutError naming
// it; device errors and faults propagate (FaultError), with the coil left at 0 A. Cancellation
// (the `cancelled` callback turning true) stops the ramp and returns what was recorded with
// `interrupted` set.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "palp/analysis/indentation.hpp"
#include "palp/analysis/pressure.hpp"
#include "palp/probe.hpp"
#include "palp/recording.hpp"

namespace palp {

/// The two protocols: 1D (every 100 ms, 5 repetitions: our choice, the paper gives no
/// top current for 1D) and 2D (every 25 ms, 3 repetitions, paper §V-A). Both 0.5 → 3 A by 0.01 A,
/// symmetric unload, 5 mm displacement limit.
enum class IndentationPreset { one_d, two_d };
const char* preset_name(IndentationPreset p);  ///< "1d", "2d"

/// The experiment's settings, SI units.
struct IndentationSettings {
  double start_A = 0.5;             ///< first step (and the float current), A
  double stop_A = 3.0;              ///< top step, A
  double step_A = 0.01;             ///< increment between steps, A
  double dwell_s = 0.1;             ///< time on each step, s
  int repetitions = 5;              ///< load/unload cycles
  bool unload = true;               ///< symmetric unload back to start_A
  double displacement_limit_m = 5e-3;  ///< turn round this far from the ramp's start; 0: none
  double stream_rate_Hz = 1000;     ///< ≤ 1000 Hz, and dividing the device's control rate
  bool zero_pressure = true;        ///< zero the pressure channels first
  double zero_pressure_s = 0.5;     ///< averaging time of that zeroing, s
  double settle_s = 1.2;            ///< device time the floating coil settles before the ramp
                                    ///< (free-air ring-down: zeta 0.26 at 16.5 rad/s)
  analysis::IndentationParams analysis;  ///< the analysis' instrument constants and options

  static IndentationSettings preset(IndentationPreset p);
  /// The device program these settings give.
  RampProgram ramp_program() const;
  /// Device time of the whole ramp without a displacement limit, s.
  double ramp_duration_s() const;
  /// Throws ConfigError naming the first bad setting.
  void validate() const;
};

/// Progress, handed to the callback from the calling thread (a few times a second).
struct IndentProgress {
  std::string phase;     ///< "releasing the coil", "zeroing pressures", "floating the coil", "ramp"
  double fraction = 0;   ///< of the ramp's nominal duration, 0..1 (a turned-round ramp ends early)
  int repetition = 0;    ///< the device's repetition counter, from 0
  double z_m = 0;        ///< the newest sample's position, m
  double i_A = 0;        ///< the newest sample's measured current, A
};
using IndentProgressFn = std::function<void(const IndentProgress&)>;

/// What one indentation gave.
struct IndentationRun {
  IndentationSettings settings;
  /// The ramp's samples, in lab units, with the sidecar (program, device, calibration, zeroing,
  /// and in extra: "stream", "gaps", "samples_missing", "float_z_mm", "interrupted").
  Recording recording;
  DeviceInfo device;
  ProgramResult program;          ///< how the ramp ended (completed, stopped_by_host, ...)
  bool interrupted = false;       ///< stopped by `cancelled`
  std::uint64_t samples_missing = 0;
  double float_z_m = 0;           ///< where the floating coil rested before the ramp (encoder)
  /// All repetitions pooled (the model fits, AIC, contact point, descriptors), or the reason
  /// there is none (e.g. "too few loading samples ...").
  std::optional<analysis::IndentationResult> analysis;
  /// Each repetition alone, with mean and s.d. of the descriptors over repetitions.
  std::optional<analysis::RepetitionSummary> repetitions;
  std::string analysis_reason;    ///< why analysis/repetitions are absent
  /// The pressure–force test: each recorded channel (p1..p6) against the object force F_o on the
  /// loading branches, with the chosen model's contact point (analysis/pressure.hpp); absent with
  /// pressure_reason without a contact point or pressure columns.
  std::optional<analysis::PressureResult> pressure;
  std::string pressure_reason;
};

/// Runs the quasi-static indentation at the probe's current position (see the top of this file).
IndentationRun indent(Probe& probe, const IndentationSettings& settings,
                      const IndentProgressFn& progress = {},
                      const std::function<bool()>& cancelled = {});

/// The analysis of a recording as indent() does it (pooled and per repetition, then the pressure
/// channels); fills run.analysis, run.repetitions and run.pressure, or the reasons the data give
/// none (a DataError's text). A bad analysis setting throws ConfigError. Exposed for
/// re-analysing a loaded run.
void analyze_run(IndentationRun& run);

/// A recording's columns as the analysis' Curve (z in m, i in A, repetitions; the commanded
/// current when recorded, which marks the staircase's plateaus).
analysis::Curve curve_of(const Recording& r);

/// Puts the K_f(stroke) table of a recording's sidecar (its calibration's kf_table) and the
/// stroke origin into p, so the analysis uses K_f at each sample's stroke position instead of
/// the constant. Throws ConfigError when the sidecar gives no stroke origin (with its reason)
/// or no table.
void use_kf_table_of(const Sidecar& sidecar, analysis::IndentationParams& p);

}  // namespace palp
