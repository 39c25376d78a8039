// SPDX-License-Identifier: Apache-2.0
// RobotWorld: the one shared world of palp-sim with the robot on (--robot-port): the probe hangs
// on the arm's flange, the phantom sits in the robot's base frame, and each virtual tick
//
//   1. the bridge (its cycle every cycle_ms) and the arm advance by the tick;
//   2. the tip apex at stroke origin, in the phantom frame,
//        inverse(phantom_frame) * flange * probe_tcp,
//      goes to the plant with Plant::move_mount (so the contact sees the approach speed), with
//      the probe's axis, the flange's +z in the phantom frame, as Plant::set_probe_axis (the
//      contact is taken along it at its angle to the surface normal: hil/plant/README.md
//      "Oblique contact") and the coil's weight along that axis, the cosine of the flange's +z
//      against the base frame's -z, as Plant::set_gravity_axis_cosine. An axis more than ~80
//      degrees from the phantom's +z cannot press into its top: the mount is parked 1 m above;
//   3. the controller's contact-output line reaches the bridge's digital input 1 after
//      input_latency_ms of virtual time;
//   4. the external force on the TCP is the material's force on the tip,
//      Plant::contact_force_vector_N (against the probe's axis, plus the lateral part an
//      oblique contact has), in the base frame (the bridge reports it, with noise).
//
// The probe's axis (the coil's +stroke) is the flange's +z; the phantom's +z points into the
// specimen. The initial flange pose puts the tip start_above_mm above the phantom origin (or at
// start_tip_mm in the base frame) with the flange's axes along the phantom frame's (the probe
// pointing into the specimen).
//
// As the Modbus handler it applies the host's writes at the next bridge cycle, except that a
// write that asks the robot to act (a new command, a stop) while a contact event holds virtual
// time is the host's reaction: it releases the hold and lands reaction_latency after the event,
// as device bytes do (Simulation::host_reaction). A closed connection stops a moving arm.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "palp/plant/robot_arm.hpp"
#include "palp/sim/modbus_server.hpp"
#include "palp/sim/plant_link.hpp"
#include "palp/sim/robot_bridge.hpp"
#include "palp/sim/simulation.hpp"

namespace palp::sim {

struct RobotWorldOptions {
  double probe_tcp_mm[3] = {0, 0, 200};          ///< tip apex at stroke origin, flange frame
  double phantom_frame_mm[3] = {600, 0, 300};    ///< phantom origin in the base frame
  double phantom_frame_deg[3] = {0, 0, 180};     ///< phantom frame's A, B, C in the base frame
  double start_above_mm = 50;                    ///< initial tip height above the phantom origin
  bool start_at_tip_mm = false;                  ///< start with the tip at start_tip_mm instead
  double start_tip_mm[3] = {0, 0, 0};            ///< initial tip position, base frame
  double input_latency_ms = 1.0;                 ///< contact line -> digital input 1, virtual
  RobotBridgeOptions bridge;
  plant::RobotArmConfig arm;
};

class RobotWorld final : public ModbusHandler {
 public:
  /// sim: the simulation whose ticks drive the world (its holds and tick period).
  RobotWorld(Simulation& sim, RobotWorldOptions options);

  /// One virtual tick, before the plant steps: advances the bridge and the arm, moves the
  /// plant's mount, feeds the digital input and the force.
  void tick(double dt_s, plant::Plant& plant, bool contact_line);
  /// The wall clock for the bridge's watchdog (palp-sim sets it every loop).
  void set_wall_us(std::uint64_t wall_us) { wall_us_ = wall_us; }

  // ModbusHandler
  ModbusException read(std::uint16_t address, std::uint16_t count, std::uint16_t* out) override;
  ModbusException write(std::uint16_t address, std::span<const std::uint16_t> regs,
                        bool single) override;
  void closed() override { bridge_.connection_closed(); }

  RobotBridge& bridge() { return bridge_; }
  plant::RobotArm& arm() { return arm_; }
  /// The tip apex at stroke origin in the phantom frame, m (the plant's mount).
  void tip_in_phantom(double out[3]) const;
  /// The probe's axis (the flange's +z) as a unit vector in the phantom frame.
  std::array<double, 3> probe_axis_in_phantom() const;
  const RobotWorldOptions& options() const { return options_; }

 private:
  static plant::Transform start_flange(const RobotWorldOptions& o);

  Simulation& sim_;
  RobotWorldOptions options_;
  plant::Transform phantom_frame_, phantom_inverse_, probe_tcp_;
  plant::RobotArm arm_;
  RobotBridge bridge_;
  std::uint64_t wall_us_ = 0;
  std::vector<bool> line_delay_;  // ring of contact-line levels, one per tick
  std::size_t line_at_ = 0;
  bool placed_ = false;  // the plant's mount is where the stationary arm holds the tip
};

/// The model plant with the arm carrying the probe: RobotWorld::tick before every plant step.
class ArmMountedPlant final : public PlantLink {
 public:
  ArmMountedPlant(std::unique_ptr<ModelPlant> plant, RobotWorld& world, const Simulation& sim)
      : plant_(std::move(plant)), world_(world), sim_(sim) {}
  void step(double dt_s, double v_coil_V) override {
    world_.tick(dt_s, plant_->model(), sim_.contact_line());
    plant_->step(dt_s, v_coil_V);
  }
  float current_sense_A() override { return plant_->current_sense_A(); }
  std::int32_t encoder_counts() override { return plant_->encoder_counts(); }
  std::array<std::uint16_t, 6> pressure_codes() override { return plant_->pressure_codes(); }
  float supply_V() override { return plant_->supply_V(); }
  ModelPlant& inner() { return *plant_; }

 private:
  std::unique_ptr<ModelPlant> plant_;
  RobotWorld& world_;
  const Simulation& sim_;
};

}  // namespace palp::sim
