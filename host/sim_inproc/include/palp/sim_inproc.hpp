// SPDX-License-Identifier: Apache-2.0
// palp-sim linked into the program: the simulated instrument (hil/sim's Instrument: the real
// firmware core against the plant, in virtual time) behind a palp::Transport, with no process
// and no socket — for tests and a lab's CI that check their tooling against the simulator.
//
//   palp::sim::InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
//   palp::Probe probe(sim.transport());          // or palp::Probe("sim+inproc://solid_1d?...")
//   sim.control("drop-frames 5");                // palp-sim's control channel, same answers
//
// Link the palp_sim_inproc library (it links hil/sim; the SDK's palp_device does not). Linking
// it also makes open_transport() accept sim+inproc://PHANTOM[?key=value&...] with the keys
// seed, mount_mm (x,y,z), hold_timeout_ms, reaction_latency_ms, serial and board (InprocOptions); each
// such URI opens a simulator of its own.
//
// Time model. Virtual time advances only inside the transport's read(): read() hands the bytes
// write() queued to the core, then runs control ticks until device bytes exist or `timeout` of
// VIRTUAL time has run, and returns as soon as bytes exist. So the simulation runs as fast as
// the reader reads (the Probe's I/O thread reads all the time: a 60 s program ends in a few s of
// wall time), and stops when nobody reads. The rules of hil/README.md hold as in palp-sim:
//   - it stalls rather than drops: device bytes the reader has not taken stop virtual time;
//   - a contact event holds virtual time until the host's next bytes (or a robot command)
//     come, or hold_timeout_ms of WALL time pass; read() then waits in wall time, up to its
//     timeout, and the reaction lands reaction_latency_ms of virtual time after the event;
//   - the controller's host-heartbeat watchdog counts on the WALL clock (std::chrono::
//     steady_clock), as palp-sim feeds it: the Probe's heartbeats go out every fifth of the
//     timeout in wall time, so fast virtual time never trips it, and a host that stops sending
//     for longer than the timeout trips it at the first tick it lets run afterwards. (As with
//     palp-sim, a Probe whose I/O thread gets no CPU for longer than the timeout trips it too:
//     here that thread also runs the simulation.)
// `pace` is refused: pacing against wall time is palp-sim's (use sim://).
//
// The robot (InprocOptions::robot): the robot bridge emulator on a Modbus TCP server on a
// loopback port (robot_uri()), sharing the simulation, with the probe on the arm. It is served
// from inside read() (no thread of its own): while a device transport is read. A robot client
// alone does not run virtual time (palp-sim's does); such tests use palp-sim.
//
// Thread-safety: as every Transport (one reader, one writer at a time); control(),
// virtual_s() and transport() may be called from any thread.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "palp/transport.hpp"

namespace palp::sim {

struct InprocOptions {
  std::string phantom = "none";             ///< a shipped phantom ("solid_1d", "pad_2d", ...) or "none"
  std::array<double, 3> mount_mm{0, 0, 0};  ///< the tip at stroke origin, phantom frame (robot off)
  std::uint64_t seed = 1;                   ///< noise seed (the same seed repeats a run)
  double hold_timeout_ms = 1000.0;          ///< wall time a contact event waits for the host
  double reaction_latency_ms = 2.0;         ///< virtual time from an event to the reaction
  std::string serial = "SIM-0001";          ///< the serial number the device reports
  std::string board = "palp-sim";           ///< the board name the device reports (DeviceInfo.board)
  bool robot = false;  ///< the robot bridge emulator with palp-sim's default frames (robot_uri())
  /// With robot: virtual time from the probe's contact-output line to the bridge's digital
  /// input 1 (palp-sim's --robot-input-latency-ms; at least one tick)
  double robot_input_latency_ms = 1.0;

  /// The options a sim+inproc:// URI gives; ConfigError naming the URI and the bad parameter.
  static InprocOptions from_uri(const Uri& uri);
};

class InprocSimulator {
 public:
  /// Builds the instrument (and with robot, listens on a loopback port). Throws ConfigError for
  /// an unknown phantom, ConnectionError when the robot's port cannot be opened.
  explicit InprocSimulator(InprocOptions options = {});
  ~InprocSimulator();
  InprocSimulator(const InprocSimulator&) = delete;
  InprocSimulator& operator=(const InprocSimulator&) = delete;

  /// A device link (Probe(sim.transport())). One at a time, like palp-sim's socket: a second
  /// while the first is open throws ConnectionError. It keeps the simulation alive on its own;
  /// a new one after the first was closed meets the same simulation.
  std::unique_ptr<Transport> transport();
  /// One line of palp-sim's control channel (control.hpp); returns its answer ("ok ..." or
  /// "error: ...").
  std::string control(const std::string& line);
  /// "sim+inproc://PHANTOM": what the transports report as their uri().
  const std::string& uri() const { return uri_; }
  /// "modbus://127.0.0.1:P" with the robot on; "" without.
  std::string robot_uri() const;
  double virtual_s() const;

  struct Core;  // the shared state (sim_inproc.cpp)

 private:
  std::shared_ptr<Core> core_;
  std::string uri_;
};

}  // namespace palp::sim
