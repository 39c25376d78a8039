// SPDX-License-Identifier: Apache-2.0
// palp-sim: the probe controller's firmware core and the physical model in virtual time, served
// over a loopback socket with the device protocol, plus a control channel for the simulator's
// own knobs, and with --robot-port the KUKA robot bridge (Modbus TCP) carrying the probe
// (hil/README.md). This file parses the options and handles signals; the loop is sim::Server
// (palp_sim_server).
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "palp/plant/phantom.hpp"
#include "palp/sim/byte_server.hpp"
#include "palp/sim/control.hpp"
#include "palp/sim/instrument.hpp"
#include "palp/sim/modbus_server.hpp"
#include "palp/sim/server.hpp"

namespace {

using namespace palp;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

struct Options {
  std::string listen = "127.0.0.1";
  std::uint16_t port = 7070;
  std::string unix_path;
  std::uint16_t control_port = 7071;
  std::string phantom = "none";
  std::vector<double> mount_mm{0.0, 0.0, 0.0};
  std::uint64_t seed = 1;
  std::string pace = "realtime";
  double hold_timeout_ms = 1000.0;
  double reaction_latency_ms = 2.0;
  std::string serial = "SIM-0001";
  std::string board = "palp-sim";
  int robot_port = -1;  // -1: the robot bridge is off
  std::vector<double> probe_tcp_mm{0.0, 0.0, 200.0};
  std::vector<double> phantom_frame_mm{600.0, 0.0, 300.0};
  std::vector<double> phantom_frame_deg{0.0, 0.0, 180.0};
  double robot_cycle_ms = 1.0;
  std::vector<double> robot_start_mm;  // empty: the tip 50 mm above the phantom origin
  double robot_input_latency_ms = 1.0;
};

double pace_factor(const std::string& pace) {
  std::string error;
  const auto c = sim::parse_control("pace " + pace, error);
  if (!c) throw CLI::ValidationError("--pace", error);
  return std::get<sim::cmd::Pace>(*c).factor;
}

sim::InstrumentOptions instrument_options(const Options& o) {
  sim::InstrumentOptions i;
  i.phantom = o.phantom;
  for (std::size_t k = 0; k < 3; ++k) i.mount_mm[k] = o.mount_mm[k];
  i.seed = o.seed;
  i.hold_timeout_ms = o.hold_timeout_ms;
  i.reaction_latency_ms = o.reaction_latency_ms;
  i.serial = o.serial;
  i.board = o.board;
  i.git_hash = PALP_GIT_HASH;
  i.robot = o.robot_port >= 0;
  sim::RobotWorldOptions& w = i.world;
  for (std::size_t k = 0; k < 3; ++k) {
    w.probe_tcp_mm[k] = o.probe_tcp_mm[k];
    w.phantom_frame_mm[k] = o.phantom_frame_mm[k];
    w.phantom_frame_deg[k] = o.phantom_frame_deg[k];
  }
  if (o.robot_start_mm.size() == 3) {
    w.start_at_tip_mm = true;
    for (std::size_t k = 0; k < 3; ++k) w.start_tip_mm[k] = o.robot_start_mm[k];
  }
  w.bridge.cycle_ms = o.robot_cycle_ms;
  w.bridge.seed = o.seed;
  w.input_latency_ms = o.robot_input_latency_ms;
  return i;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"palp-sim: the palp probe controller's firmware core against a physical model, in "
               "virtual time, served over a loopback socket (hil/README.md)"};
  app.add_option("--listen-address", o.listen, "IPv4 address to listen on (loopback by default)")
      ->capture_default_str();
  app.add_option("--port", o.port, "TCP port of the device protocol (0: pick a free one)")
      ->capture_default_str();
  app.add_option("--unix", o.unix_path, "serve the device protocol on this Unix socket instead");
  app.add_option("--control-port", o.control_port, "TCP port of the control channel (0: free)")
      ->capture_default_str();
  std::string phantoms = "specimen under the probe: none";  // and every shipped phantom
  for (const std::string_view name : palp::plant::shipped_phantom_names())
    phantoms += ", " + std::string(name);
  app.add_option("--phantom", o.phantom, phantoms)
      ->capture_default_str();
  app.add_option("--mount-mm", o.mount_mm,
                 "probe mount x y z in mm: the tip at the stroke origin, phantom frame")
      ->expected(3);
  app.add_option("--seed", o.seed, "noise seed (the same seed repeats a run)")->capture_default_str();
  app.add_option("--pace", o.pace, "realtime, fast, or a factor of real time")->capture_default_str();
  app.add_option("--hold-timeout-ms", o.hold_timeout_ms,
                 "wall time a contact event waits for the host's reaction")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--reaction-latency-ms", o.reaction_latency_ms,
                 "virtual time from an event to the host's reaction")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--serial", o.serial, "serial number the device reports")->capture_default_str();
  app.add_option("--board", o.board,
                 "board name the device reports (DeviceInfo.board; e.g. stm32g474 to try `palpctl "
                 "flash` up to the bootloader)")
      ->capture_default_str();
  app.add_option("--robot-port", o.robot_port,
                 "serve the KUKA robot bridge (Modbus TCP) on this port (0: a free one); "
                 "without it the robot is off and --mount-mm places the probe")
      ->check(CLI::Range(0, 65535));
  app.add_option("--probe-tcp-mm", o.probe_tcp_mm,
                 "robot: the tip apex at stroke origin in the flange frame, x y z in mm")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--phantom-frame-mm", o.phantom_frame_mm,
                 "robot: the phantom frame's origin in the robot base frame, x y z in mm")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--phantom-frame-deg", o.phantom_frame_deg,
                 "robot: the phantom frame's orientation in the base frame, KUKA A B C in deg")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--robot-start-mm", o.robot_start_mm,
                 "robot: start with the tip at this base-frame position, x y z in mm (default: "
                 "50 mm above the phantom origin), the probe along the phantom's +z")
      ->expected(3);
  app.add_option("--robot-cycle-ms", o.robot_cycle_ms, "robot: the bridge's cycle, virtual ms")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 20.0));
  app.add_option("--robot-input-latency-ms", o.robot_input_latency_ms,
                 "robot: contact-output line to digital input 1, virtual ms")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  CLI11_PARSE(app, argc, argv);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  try {
    if (o.listen != "127.0.0.1")
      std::fprintf(stderr, "palp-sim: warning: listening on %s, not only on loopback\n",
                   o.listen.c_str());
    pace_factor(o.pace);
    if (o.robot_port >= 0 && app.count("--mount-mm") > 0)
      std::fprintf(stderr, "palp-sim: warning: --mount-mm is ignored with --robot-port: the arm "
                           "places the probe (--robot-start-mm)\n");
    sim::ByteServer device = o.unix_path.empty() ? sim::ByteServer::tcp(o.listen, o.port)
                                                 : sim::ByteServer::unix_socket(o.unix_path);
    sim::ByteServer control = sim::ByteServer::tcp(o.listen, o.control_port);
    std::unique_ptr<sim::ModbusServer> robot;
    if (o.robot_port >= 0)
      robot = std::make_unique<sim::ModbusServer>(o.listen, static_cast<std::uint16_t>(o.robot_port));
    sim::Server server(std::make_unique<sim::Instrument>(instrument_options(o)), std::move(device),
                       std::move(control), std::move(robot), pace_factor(o.pace));
    std::printf("%s\n", server.banner().c_str());
    std::fflush(stdout);
    server.run(g_stop);
    std::printf("palp-sim: stopped after %.3f s of virtual time\n",
                server.instrument().simulation().virtual_s());
    return 0;
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    const std::string what = e.what();  // most messages name palp-sim already
    std::fprintf(stderr, "%s%s\n", what.rfind("palp-sim: ", 0) == 0 ? "" : "palp-sim: ", what.c_str());
    return 1;
  }
}
