// Server: palp-sim's loop, serving an Instrument over sockets (hil/README.md "palp-sim: virtual
// time"): the device protocol on one ByteServer, the control channel on another, and with the
// robot on, the robot bridge's ModbusServer. One step():
//
//   - polls the robot's Modbus socket (every 0.2 ms of wall time at most) and the device socket,
//     hands the host's bytes to the simulation and answers control lines;
//   - runs up to 1 ms of virtual time, no further than wall time allows at the pace (0: as fast
//     as possible), and only while a client is connected and the host has drained the device
//     bytes (it stalls rather than drops; a held contact event holds virtual time too);
//   - sends the device bytes in order, keeping what the socket refused for the next step.
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

  /// Device bytes the host has not drained beyond which virtual time stops.
  static constexpr std::size_t kStallBytes = 64 * 1024;

 private:
  using Clock = std::chrono::steady_clock;
  std::uint64_t wall_us() const;
  bool robot_client() const { return robot_ && robot_->has_client(); }
  void resync();
  void serve_control();
  void reply(const std::string& line);

  std::unique_ptr<Instrument> instrument_;
  ByteServer device_;
  ByteServer control_;
  std::unique_ptr<ModbusServer> robot_;
  double pace_;
  Clock::time_point t0_ = Clock::now();
  std::uint64_t virtual_at_sync_ = 0;       // the pace counts virtual time from here ...
  Clock::time_point wall_at_sync_ = t0_;    // ... against wall time from here
  std::uint64_t last_robot_poll_us_ = 0;
  std::string control_line_;
  std::vector<std::uint8_t> pending_;       // device bytes the socket has not taken yet
};

}  // namespace palp::sim
