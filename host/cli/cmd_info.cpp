// SPDX-License-Identifier: Apache-2.0
// palpctl info: who the device is, the handshake, its parameters, calibration, status and health.
#include <iostream>

#include "common.hpp"
#include "palp/result.hpp"

namespace palpctl {

namespace {
int info(const Context& ctx) {
  auto probe = ctx.connect();
  json j = {{"uri", probe.uri()},
            {"sdk_version", palp::sdk_version()},
            {"device", palp::device_json(probe.info())},
            {"handshake", to_json(probe.handshake())},
            {"status", to_json(probe.status())},
            {"params", to_json(probe.params())},
            {"calibration", palp::calibration_json(probe.calibration())},
            {"health", to_json(probe.health())}};
  if (ctx.json) {
    print_json(j);
  } else {
    print_text(j);
  }
  return kOk;
}
}  // namespace

void add_info_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand(
      "info", "Connect and print device info, handshake, status, parameters, calibration and "
              "health counters (lengths in mm, times in s, stiffness in N/mm)");
  cmd->callback([&ctx] { ctx.action = [&ctx] { return info(ctx); }; });
}

}  // namespace palpctl
