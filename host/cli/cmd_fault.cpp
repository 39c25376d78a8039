// SPDX-License-Identifier: Apache-2.0
// palpctl fault show|clear: read the fault latch, or release it once its cause is gone.
#include <iostream>

#include "common.hpp"

namespace palpctl {

namespace {
void print_fault(const Context& ctx, const json& j) {
  if (ctx.json) {
    print_json(j);
  } else {
    print_text(j);
  }
}

int show(const Context& ctx) {
  auto probe = ctx.connect();
  const auto f = probe.fault();
  print_fault(ctx, {{"fault", to_json(f)}});
  return kOk;
}

int clear(const Context& ctx) {
  auto probe = ctx.connect();
  const auto before = probe.fault();
  if (before.reason != palp::proto::FaultReason::none) probe.clear_fault();
  const auto after = probe.fault();
  const bool cleared = after.reason == palp::proto::FaultReason::none;
  json j = {{"before", to_json(before)}, {"after", to_json(after)}, {"cleared", cleared}};
  print_fault(ctx, j);
  if (!cleared) {
    std::cerr << "palpctl: the fault latch is still set (" << name_of(after.reason) << ")\n";
    return kFault;
  }
  return kOk;
}
}  // namespace

void add_fault_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("fault", "Read or clear the device's fault latch");
  cmd->require_subcommand(1, 1);
  cmd->add_subcommand("show", "Print the latched fault (reason none when clear); exit 0 either way")
      ->callback([&ctx] { ctx.action = [&ctx] { return show(ctx); }; });
  cmd->add_subcommand("clear",
                      "Release the fault latch if its cause is gone; exit 6 if it stays set "
                      "(the device names the reason)")
      ->callback([&ctx] { ctx.action = [&ctx] { return clear(ctx); }; });
}

}  // namespace palpctl
