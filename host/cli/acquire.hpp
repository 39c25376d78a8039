// The acquisition both `stream` and `run` do: optional zeroing (RAM only), stream, optionally a
// device program, every sample and gap into a recording with its sidecar, progress on stderr,
// Ctrl-C stops cleanly and keeps what was recorded.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "common.hpp"

namespace palpctl {

/// What `stream` and every `run` program share on the command line.
struct AcquireOptions {
  std::string out = "run.csv";
  bool overwrite = false;
  double rate_Hz = 1000;
  double seconds = 0;  ///< stream: how long; run: see ProgramSpec::stop_after_s
  bool zero_current = false;
  bool zero_pressure = false;
  double zero_s = 0.5;
};

/// Adds --out, --overwrite, --rate-Hz, --zero-current, --zero-pressure, --zero-s to a command.
void add_acquire_options(CLI::App& cmd, AcquireOptions& o);

/// The device program of a `run`: how to load it, its parameters for the sidecar (lab units)
/// and how long it is expected to take (for progress and the wait's deadline).
struct ProgramSpec {
  std::string name;                                ///< "ramp", "sine", ...
  json params;                                     ///< as given on the command line, lab units
  double expected_s = 0;                           ///< 0 when open-ended
  double stop_after_s = 0;  ///< stop the program after this much stream time (0: at its end)
  std::function<void(palp::Probe&)> load;
  std::optional<palp::RampProgram> ramp;  ///< a ramp: its samples get repetition numbers
};

/// Runs the acquisition; program is empty for `stream`. Returns the exit code.
int acquire(const Context& ctx, const AcquireOptions& o, const std::optional<ProgramSpec>& program);

}  // namespace palpctl
