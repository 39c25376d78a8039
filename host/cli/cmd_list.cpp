// SPDX-License-Identifier: Apache-2.0
// palpctl list: every controller on this machine's USB, with serial, firmware and URIs.
#include <iostream>

#include "common.hpp"
#include "palp/discovery.hpp"

namespace palpctl {

namespace {
int list(const Context& ctx) {
  const auto devices = palp::list_devices();
  if (ctx.json) {
    json out = json::array();
    for (const auto& d : devices) {
      char id[16];
      std::snprintf(id, sizeof id, "%04x:%04x", d.vid, d.pid);
      json j = {{"serial", d.serial},       {"firmware_version", d.firmware_version},
                {"product", d.product},     {"usb_id", id},
                {"uris", d.uris}};
      if (!d.note.empty()) j["note"] = d.note;
      out.push_back(j);
    }
    print_json(out);
    return kOk;
  }
  if (devices.empty()) {
    std::cout << "no palp controller found on USB (a UART-attached board is reached with "
                 "--uri serial:///dev/ttyX, palp-sim with --uri tcp://HOST:PORT)\n";
    return kOk;
  }
  for (const auto& d : devices) {
    std::cout << (d.serial.empty() ? "(serial unreadable)" : d.serial) << "  firmware "
              << (d.firmware_version.empty() ? "?" : d.firmware_version) << "  " << d.product;
    for (const auto& u : d.uris) std::cout << "  " << u;
    std::cout << '\n';
    if (!d.note.empty()) std::cout << "  note: " << d.note << '\n';
  }
  return kOk;
}
}  // namespace

void add_list_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("list", "List the controllers on this machine's USB (no --uri "
                                          "needed); an empty list is not an error");
  cmd->callback([&ctx] { ctx.action = [&ctx] { return list(ctx); }; });
}

}  // namespace palpctl
