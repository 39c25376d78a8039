// SPDX-License-Identifier: Apache-2.0
// The recorder: stream a probe into a recording (run.csv + run.json, recording.hpp,
// docs/recording-format.md), optionally while a device program runs. It writes exactly the
// files `palpctl stream` and `palpctl run` write (palpctl calls it): every sample, every gap
// (extra.gaps, extra.samples_missing), the link's health at the end (extra.health), the device,
// its params, calibration and zeroing, and the program with its parameters and result.
//
//   std::atomic<bool> stop{false};                       // set from a Ctrl-C handler, a GUI, ...
//   palp::Probe probe("usb://");
//   palp::RecordResult r = palp::record(probe, {
//       .out = "data/ramp1",                              // data/ramp1.csv + data/ramp1.json
//       .rate_Hz = 1000,
//       .program = palp::RampProgram{.start_A = 0.1f, .stop_A = 1.0f, .step_A = 0.1f,
//                                    .dwell_s = 0.5f, .repetitions = 3, .unload = 1},
//       .zero_current = true,                             // device RAM only, kept in the sidecar
//       .cancelled = [&] { return stop.load(); },
//       .progress = [](const palp::RecordProgress& p) { show(p.samples, p.expected_samples); }});
//   // r.samples, r.samples_missing, r.gaps, r.interrupted, r.program->end
//
// Or in two steps, so that an existing recording is refused before a device is opened:
//
//   palp::Recorder recorder(settings);                    // ConfigError: run.csv already exists
//   palp::Probe probe(uri);
//   palp::RecordResult r = recorder.run(probe);
//
// What run() does, in order: zeroes the current offset and/or the pressure channels when asked
// (RAM only, each averaged over zero_s); configures the stream at rate_Hz; loads the program;
// starts the stream and then the program; records until
//   - without a program: duration_s of stream time (exactly round(duration_s x rate) sample
//     indices from the first: later samples are not written);
//   - with a program: its end, or duration_s of stream time when given (the program is then
//     stopped and its end is stopped_by_host);
//   - cancelled() returns true (checked about every 50 ms): the recording keeps what came and
//     says interrupted;
//   - an error (a lost reply, a stream silent for reply_timeout_s + 5 s, a program that does not
//     end within 2 x its expected time + 30 s + reply_timeout_s).
// Whatever ends it, run() then stops what it started, each step tried even when one before it
// failed: the program (ProgramStop: the coil back to 0 A), the stream (the samples still queued
// are kept), and after an error in a program's recording Probe::make_safe (no program, 0 A, no
// stream). It reads the health counters and the fault (when the program did not end) and writes
// the recording when the program (without one, the stream) started and at least one sample came,
// after an error with extra.error holding the message, and then rethrows the first error (a
// program the device refuses to load or start leaves no files). A cancelled recording is not an error: run()
// returns with interrupted set. A plain stream never drives the coil: the device keeps holding
// whatever it held before.
//
// Lab units in the files (recording.hpp); the settings are in SI like the rest of the SDK (s, Hz,
// A), the program structs are the protocol's (probe.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "palp/probe.hpp"
#include "palp/recording.hpp"

namespace palp {

/// The device programs a recording can run: those `palpctl run` loads.
using RecordedProgram = std::variant<HoldProgram, RampProgram, SineProgram, SweepProgram>;

/// The program's name as the sidecar's program.kind holds it: "hold", "ramp", "sine", "sweep".
std::string program_kind(const RecordedProgram& program);
/// How long the program runs by its parameters, s (device time); 0 when open-ended (a sine with
/// cycles = 0). A ramp's staircase and unload and a sweep's settle and measure cycles counted as
/// the firmware schedules them.
double expected_duration_s(const RecordedProgram& program);

/// What the progress callback sees.
struct RecordProgress {
  std::uint64_t samples = 0;           ///< written so far
  std::uint64_t expected_samples = 0;  ///< round(expected time x rate); 0 when open-ended
  std::uint64_t samples_missing = 0;   ///< in the gaps so far
  bool finished = false;               ///< the last call: the stream is stopped
};

struct RecordSettings {
  /// The recording: `run` or `run.csv` (recording_csv_path), its sidecar beside it.
  std::filesystem::path out = "run.csv";
  Overwrite overwrite = Overwrite::no;
  double rate_Hz = 1000;  ///< stream rate, Hz (divides the device's control rate)
  /// Without a program: how long to record, s of stream time (required, > 0). With one: stop the
  /// program after this long (0: at its end; required when the program is open-ended).
  double duration_s = 0;
  std::optional<RecordedProgram> program = std::nullopt;
  bool zero_current = false;   ///< zero the current-sense offset first (device RAM only)
  bool zero_pressure = false;  ///< zero the pressure channels first, unloaded (device RAM only)
  double zero_s = 0.5;         ///< averaging time of each zeroing, s
  /// The link's reply timeout, s (ConnectOptions::timeout): the stream may be silent for this
  /// + 5 s, and the program's wait gets it on top of 2 x its expected time + 30 s.
  double reply_timeout_s = 2.0;
  /// The sidecar's program_reason when no program runs.
  std::string no_program_reason = "no program ran";
  /// Polled about every 50 ms; true ends the recording early (interrupted).
  std::function<bool()> cancelled = nullptr;
  /// Called after every batch of samples, from run()'s thread, and once with finished set.
  std::function<void(const RecordProgress&)> progress = nullptr;
};

struct RecordResult {
  bool written = false;              ///< false when nothing was recorded (then no file was written)
  std::filesystem::path csv;         ///< the recording's final names
  std::filesystem::path sidecar;
  std::uint64_t samples = 0;
  std::uint64_t samples_missing = 0;
  std::size_t gaps = 0;              ///< gap records (extra.gaps)
  bool interrupted = false;          ///< cancelled() ended it
  std::optional<ProgramResult> program;  ///< how the program ended; empty without one
  /// The sidecar as written (run.json: program block, health, gaps, ..., with the writer's
  /// sdk_version, created_utc, csv_rows and csv_crc32); empty when nothing was written.
  Sidecar sidecar_written;
};

/// One recording. Not copyable; run() once.
class Recorder {
 public:
  /// Checks the settings (ConfigError: duration_s not above 0 without a program, an open-ended
  /// program without duration_s, rate_Hz or zero_s not positive) and claims the files: a
  /// ConfigError when run.csv or run.json exists and overwrite is no, before any device is used.
  explicit Recorder(RecordSettings settings);
  ~Recorder();
  Recorder(Recorder&&) noexcept;
  Recorder& operator=(Recorder&&) noexcept;

  /// Records from `probe` (connected; nothing else may read its stream meanwhile). See the top
  /// of this header for what it does and how every exit path leaves the device.
  RecordResult run(Probe& probe);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Recorder(settings).run(probe).
RecordResult record(Probe& probe, RecordSettings settings);

}  // namespace palp
