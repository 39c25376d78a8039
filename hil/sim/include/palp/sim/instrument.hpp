// SPDX-License-Identifier: Apache-2.0
// Instrument: the simulated instrument palp-sim serves, without any socket: the controller's
// firmware core against the plant in a Simulation, and with the robot on, the arm that carries
// the probe (RobotWorld). It applies the control channel's commands (control.hpp); the ones
// about how the instrument is served (pace, the Modbus server's knobs, the clients in status)
// go to its Serving, so palp-sim's socket Server and the SDK's in-process transport share one
// definition of every knob.
//
// Not thread-safe: whoever serves it drives it from one thread at a time.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "palp/plant/plant.hpp"
#include "palp/sim/control.hpp"
#include "palp/sim/modbus_server.hpp"
#include "palp/sim/robot_world.hpp"
#include "palp/sim/sensor_faults.hpp"
#include "palp/sim/simulation.hpp"

namespace palp::sim {

struct InstrumentOptions {
  std::string phantom = "none";                ///< a shipped phantom or "none" (free air)
  std::array<double, 3> mount_mm{0, 0, 0};     ///< robot off: the tip at stroke origin, phantom frame
  std::uint64_t seed = 1;                      ///< noise seed (the same seed repeats a run)
  double hold_timeout_ms = 1000.0;             ///< wall time a held event waits for the host
  double reaction_latency_ms = 2.0;            ///< virtual time from an event to the reaction
  std::string serial = "SIM-0001";             ///< the serial number the device reports
  std::string git_hash = "unknown";            ///< DeviceInfo.git_hash
  std::string board = "palp-sim";              ///< DeviceInfo.board (a test of `palpctl flash` poses as a board)
  bool robot = false;                          ///< the arm carries the probe (and mount_mm is unused)
  RobotWorldOptions world{};                   ///< with robot: frames, start pose, bridge
};

/// How the instrument is served: what a control command about the serving side needs.
class Serving {
 public:
  virtual ~Serving() = default;
  /// pace <factor> (0: as fast as possible). Returns "" or the reason it is refused.
  virtual std::string set_pace(double factor) = 0;
  virtual double pace() const = 0;
  virtual bool device_client() const = 0;
  /// The robot bridge's Modbus server, null when there is none.
  virtual ModbusServer* robot_server() = 0;
  /// Fields the serving side adds to the status line (" name=value ...", or empty).
  virtual std::string status_fields() const { return {}; }
};

class Instrument {
 public:
  /// Throws plant::PhantomError for an unknown or malformed phantom.
  explicit Instrument(InstrumentOptions options);
  Instrument(const Instrument&) = delete;
  Instrument& operator=(const Instrument&) = delete;

  Simulation& simulation() { return *sim_; }
  /// The arm's world, null with the robot off (it is the Modbus servers' handler).
  RobotWorld* world() { return world_.get(); }
  const InstrumentOptions& options() const { return o_; }

  /// Parses and applies one control line; returns the reply line ("ok ..." or "error: ...").
  std::string control(std::string_view line, Serving& serving);
  std::string apply(const ControlCommand& c, Serving& serving);

 private:
  std::unique_ptr<PlantLink> make_plant(const std::string& phantom, std::uint64_t seed);
  std::string apply_fault(const cmd::Fault& fault);
  plant::Plant& model();
  void mount(double x_mm, double y_mm, double z_mm);
  void place_on_arm();
  std::string rebuild_plant(const std::string& phantom, std::uint64_t seed);
  std::string status(Serving& serving);

  InstrumentOptions o_;
  fw::DeviceIdentity identity_;
  SensorFaults faults_;  // the plant's FaultyPlant applies them (declared first: outlives it)
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<RobotWorld> world_;
  std::string phantom_;
  std::uint64_t seed_;
  std::array<double, 3> mount_mm_{};
};

}  // namespace palp::sim
