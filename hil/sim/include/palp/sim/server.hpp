// SPDX-License-Identifier: Apache-2.0
// Server: palp-sim's loop, serving an Instrument over sockets (hil/README.md "palp-sim: virtual
// time"): the device protocol on one ByteServer, the control channel on another, and with the
// robot on, the robot bridge's ModbusServer. One step():
//
//   - polls the robot's Modbus socket (every 0.2 ms of wall time at most) and the device socket,
//     and hands the host's bytes to the simulation, after a tick at their wall time unless one
//     ran within 0.5 ms (so the heartbeat watchdog's overdue check comes before they feed it);
//   - runs up to 1 ms of virtual time, no further than wall time allows at the pace (0: as fast
//     as possible); a held contact event holds virtual time;
//   - answers control lines;
//   - sends the device bytes in order, keeping what the socket refused for the next step.
//
// Host loss (hil/README.md "Host loss"): with no client, virtual time runs at real time,
// sleeping between steps, whatever the pace, so the core's heartbeat watchdog (wall clock) trips
// as on hardware. A host that does not drain the device bytes stalls virtual time (nothing is
// dropped) while it still sends something at least every heartbeat timeout; a host silent for
// longer is lost: virtual time runs on at real time and the device frames it does not take are
// dropped whole and counted (status: host_dropped_frames), as a device whose USB endpoint is
// not read loses stream data.
//
// palp-sim's main() parses the options, builds the Server and calls run(); tests call step().
#pragma once

#include <chrono>
#include <csignal>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "palp/sim/byte_server.hpp"
#include "palp/sim/instrument.hpp"
#include "palp/sim/modbus_server.hpp"

namespace palp::sim {

class Server final : public Serving {
 public:
  /// robot: the Modbus server of the instrument's arm; null when the instrument has no robot
  /// (std::invalid_argument when one is given without the other). pace: 0 as fast as possible,
  /// 1 real time, N times real time.
  Server(std::unique_ptr<Instrument> instrument, ByteServer device, ByteServer control,
         std::unique_ptr<ModbusServer> robot, double pace);

  /// "palp-sim listening on tcp://... (device protocol), control on tcp://...[, robot bridge
  /// on tcp://...]" (palp-sim's first stdout line; tests read the ports from it).
  std::string banner() const;

  /// One pass of the loop; waits at most 2 ms (on the sockets, or to keep the pace).
  void step();
  /// Steps until stop becomes non-zero (palp-sim's signal handler sets it).
  void run(const volatile std::sig_atomic_t& stop);

  Instrument& instrument() { return *instrument_; }
  ByteServer& device() { return device_; }

  // Serving
  std::string set_pace(double factor) override;
  double pace() const override { return pace_; }
  bool device_client() const override { return device_.has_client(); }
  ModbusServer* robot_server() override { return robot_.get(); }

  std::string status_fields() const override;

  /// Device bytes the host has not drained beyond which virtual time stops (for a host that is
  /// not lost, see above).
  static constexpr std::size_t kStallBytes = 64 * 1024;
  /// The device port's idle rule (set by the constructor; device().set_idle_rule() changes it):
  /// a client that has sent no complete frame for 30 s, or left one unfinished for 5 s, loses
  /// the one slot. The SDK never comes near: an open Probe sends a Heartbeat every heartbeat
  /// timeout / 5 (at most 2 s) and a Ping every 0.2 s, each one whole frame in one write.
  static constexpr ByteServer::IdleRule kDeviceIdle{30'000, 5'000, 0};
  /// Control-channel line limit: a longer line is discarded up to its newline, with one error.
  static constexpr std::size_t kControlLineBytes = 4096;

  /// Device frames dropped because a lost host did not take them.
  std::uint64_t host_dropped_frames() const { return dropped_frames_; }
  /// True while no client is connected, or the device client has neither drained nor sent a
  /// byte for longer than the heartbeat timeout: virtual time runs at real time.
  bool host_lost() const { return lost_; }
  /// True when the last step() stood still for a host that is alive but does not drain: the
  /// device bytes waiting reached kStallBytes (the sockets' buffers full), and virtual time stands.
  bool host_stalled() const { return stalled_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::uint64_t wall_us() const;
  bool robot_client() const { return robot_ && robot_->has_client(); }
  void resync(double effective_pace);
  std::uint32_t paced_chunk(double effective_pace, std::uint32_t cap_ticks);
  void serve_control();
  void reply(const std::string& line);

  std::unique_ptr<Instrument> instrument_;
  ByteServer device_;
  ByteServer control_;
  std::unique_ptr<ModbusServer> robot_;
  double pace_;
  Clock::time_point t0_ = Clock::now();
  std::uint64_t virtual_at_sync_ = 0;       // the pace counts virtual time from here ...
  Clock::time_point wall_at_sync_ = t0_;    // ... against wall time from here ...
  std::uint32_t rate_at_sync_ = 0;          // ... at this control rate ...
  double pace_at_sync_ = -1;                // ... and this pace (1 while the host is lost)
  Clock::time_point host_heard_ = t0_;      // the device client's last bytes (or its connect)
  std::uint64_t last_tick_us_ = 0;          // wall_us() of the last step that ran a tick
  bool lost_ = true;
  bool stalled_ = false;
  std::uint64_t dropped_frames_ = 0;
  std::uint64_t last_robot_poll_us_ = 0;
  std::string control_line_;
  bool discarding_line_ = false;            // inside an overlong control line
  std::vector<std::uint8_t> pending_;       // device bytes the socket has not taken yet
};

}  // namespace palp::sim
