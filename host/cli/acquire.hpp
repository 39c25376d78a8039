// SPDX-License-Identifier: Apache-2.0
// What `stream` and `run` share: the recording's options, and the SDK's recorder
// (palp/recorder.hpp: optional zeroing, stream, optionally a device program, every sample and gap
// into a recording with its sidecar) with progress on stderr and Ctrl-C.
#pragma once

#include <optional>
#include <string>

#include "common.hpp"
#include "palp/recorder.hpp"

namespace palpctl {

/// What `stream` and every `run` program share on the command line.
struct AcquireOptions {
  std::string out = "run.csv";
  bool overwrite = false;
  double rate_Hz = 1000;
  double seconds = 0;  ///< stream: how long; run: stop the program after (RecordSettings::duration_s)
  bool zero_current = false;
  bool zero_pressure = false;
  double zero_s = 0.5;
};

/// Adds --out, --overwrite, --rate-Hz, --zero-current, --zero-pressure, --zero-s to a command.
void add_acquire_options(CLI::App& cmd, AcquireOptions& o);

/// Records with the SDK's recorder (palp/recorder.hpp): the program is empty for `stream`.
/// Progress on stderr, Ctrl-C stops cleanly and keeps what was recorded. Returns the exit code.
int acquire(const Context& ctx, const AcquireOptions& o,
            const std::optional<palp::RecordedProgram>& program);

}  // namespace palpctl
