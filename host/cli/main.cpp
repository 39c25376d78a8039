// SPDX-License-Identifier: Apache-2.0
// palpctl: the command-line tool over the palp SDK (README.md in this folder: commands, options,
// exit codes). Lab units at the command line: mm, A, s, Hz, Pa; each option's unit is in its name.
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <string>

#include "common.hpp"
#include "palp/probe.hpp"

int main(int argc, char** argv) {
  palpctl::Context ctx;
  ctx.uri = "sim://127.0.0.1:7070";

  CLI::App app{"palpctl: the palp probe controller from the command line (SDK " +
                   std::string(palp::sdk_version()) + ").\n"
                   "Lab units: mm, A, s, Hz, Pa; every option names its unit.\n"
                   "Exit codes: 0 ok, 1 device/runtime error, 2 usage, 3 connection, 4 timeout,\n"
                   "5 version incompatible, 6 fault, 130 interrupted.",
               "palpctl"};
  app.set_version_flag("--version", std::string("palpctl ") + palp::sdk_version());
  app.add_option("--uri", ctx.uri,
                 "The controller: usb://[SERIAL], hid://[SERIAL], serial:///dev/ttyX[?baud=N] "
                 "(a UART-attached board; 115200 baud unless told), tcp://HOST:PORT (palp-sim, "
                 "or the firmware under QEMU), sim://HOST:PORT (default from $PALP_URI, else "
                 "sim://127.0.0.1:7070)")
      ->envname("PALP_URI")
      ->capture_default_str();
  app.add_option("--timeout-s", ctx.timeout_s, "Wait this long for each reply from the device")
      ->check(palpctl::kPositive)
      ->capture_default_str();
  app.add_flag("--json", ctx.json,
               "Print results as JSON on stdout (no progress on stderr; errors as "
               "{\"error\": ...})");
  app.add_flag_callback("-v,--verbose", palpctl::log_sdk_to_stderr,
                        "Report on stderr, with the time, what the SDK recovers from on its own: "
                        "link lost and restored, requests resent, stream gaps, robot reconnects");
  app.require_subcommand(1, 1);
  app.fallthrough();  // global options may also follow the command: palpctl info --json

  palpctl::add_list_command(app, ctx);
  palpctl::add_info_command(app, ctx);
  palpctl::add_monitor_command(app, ctx);
  palpctl::add_stream_command(app, ctx);
  palpctl::add_run_command(app, ctx);
  palpctl::add_calibrate_command(app, ctx);
  palpctl::add_fault_command(app, ctx);
  palpctl::add_trace_command(app, ctx);
  palpctl::add_analyze_command(app, ctx);
  palpctl::add_indent_command(app, ctx);
  palpctl::add_map_command(app, ctx);
  palpctl::add_sweep_commands(app, ctx);
  palpctl::add_flash_command(app, ctx);
  palpctl::add_export_command(app, ctx);
  palpctl::add_report_command(app, ctx);
  palpctl::add_params_command(app, ctx);
  palpctl::add_completion_command(app, ctx);

  // every command's --help names the global options too (they may follow the command)
  const std::function<void(CLI::App*)> add_footer = [&](CLI::App* cmd) {
    for (auto* sub : cmd->get_subcommands({})) {
      sub->footer("Global options, before or after the command: --uri URI, --timeout-s S, --json, -v.\n"
                  "Exit codes: 0 ok, 1 device/runtime error, 2 usage, 3 connection, 4 timeout,\n"
                  "5 version incompatible, 6 fault, 130 interrupted.");
      add_footer(sub);
    }
  };
  add_footer(&app);
  palpctl::require_finite_numbers(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);  // prints help, the version, or the error and a hint
    return rc == 0 ? palpctl::kOk : palpctl::kUsage;
  }
  if (!ctx.action) return palpctl::kUsage;
  return palpctl::run_guarded(ctx, ctx.action);
}
