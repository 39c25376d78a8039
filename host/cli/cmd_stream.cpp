// SPDX-License-Identifier: Apache-2.0
// palpctl stream: record the stream for --seconds, no program (the device holds what it holds).
#include <memory>

#include "acquire.hpp"

namespace palpctl {

void add_stream_command(CLI::App& app, Context& ctx) {
  auto o = std::make_shared<AcquireOptions>();
  auto* cmd = app.add_subcommand(
      "stream", "Record every channel for --seconds into a recording (CSV + JSON sidecar), with "
                "progress on stderr; Ctrl-C stops early and keeps what was recorded");
  cmd->add_option("--seconds", o->seconds, "How long to record, s (device time)")
      ->required()
      ->check(kPositive);
  add_acquire_options(*cmd, *o);
  cmd->callback([&ctx, o] { ctx.action = [&ctx, o] { return acquire(ctx, *o, std::nullopt); }; });
}

}  // namespace palpctl
