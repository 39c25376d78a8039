// SPDX-License-Identifier: Apache-2.0
// The simulated world: the real firmware core (palp::fw::Controller) against a physical model, in
// virtual time, with the host link's rules from hil/README.md: results never depend on wall time,
// the simulation stalls rather than drops, and a contact event holds virtual time until the host
// reacts (or a wall-clock timeout), after which the host's reaction lands a fixed virtual latency
// after the event.
//
// Not thread-safe: palp-sim drives it from one loop.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "palp/fw/controller.hpp"
#include "palp/protocol/frame.hpp"

namespace palp::sim {

/// What the simulation needs from the physical model, tick by tick.
class PlantLink {
 public:
  virtual ~PlantLink() = default;
  /// Advances the physics by dt_s with this average coil voltage.
  virtual void step(double dt_s, double v_coil_V) = 0;
  /// The sensors as the firmware's board would read them now.
  virtual float current_sense_A() = 0;
  virtual std::int32_t encoder_counts() = 0;
  virtual std::array<std::uint16_t, 6> pressure_codes() = 0;
  /// The H-bridge supply as the board measures it, and the driver's fault line (sensor_faults.hpp
  /// makes them fail).
  virtual float supply_V() { return fw::kDefaultSupply_V; }
  virtual bool driver_fault() { return false; }
};

struct SimulationOptions {
  double reaction_latency_ms = 2.0;  ///< virtual time from an event to the host's reaction
  double hold_timeout_ms = 1000.0;   ///< wall time a held event waits for the host
  std::uint32_t drop_every = 0;      ///< drop every n-th device frame (0: none)
  std::uint32_t corrupt_every = 0;   ///< flip a bit in every n-th device frame (0: none)
};

class Simulation {
 public:
  Simulation(const fw::DeviceIdentity& identity, std::unique_ptr<PlantLink> plant,
             SimulationOptions options = {});

  /// Bytes from the host, at this wall time (µs, any epoch; it feeds the watchdog). While an
  /// event is held they wait and are delivered after the reaction latency.
  void host_bytes(const std::uint8_t* data, std::size_t size, std::uint64_t wall_us);

  /// A host reaction that does not come as device bytes (a robot-bridge write that commits a
  /// command or a stop): it releases a held event as host bytes do. Returns the tick at which
  /// it takes effect: reaction_latency after the release when an event was held (or is being
  /// released), else the current tick.
  std::uint64_t host_reaction(std::uint64_t wall_us);

  /// Runs up to max_ticks control ticks unless held; returns how many ran. The caller stops
  /// calling (stalls) while the host has not drained the device bytes. A hold ends after
  /// hold_timeout_ms, or once the host has sent nothing for the core's heartbeat timeout (it
  /// will not react; the watchdog must get its ticks to trip).
  std::uint32_t run(std::uint32_t max_ticks, std::uint64_t wall_us);

  /// Device bytes produced so far (after fault injection); takes them.
  std::vector<std::uint8_t> take_device_bytes();

  /// Virtual time: ticks, and seconds (each tick at the control rate it ran at).
  std::uint64_t ticks() const { return controller_.ticks(); }
  double virtual_s() const;
  bool holding() const { return hold_.active; }
  /// The controller's contact-output line as of the last tick (to the robot's digital input).
  bool contact_line() const { return contact_line_; }

  SimulationOptions& options() { return options_; }
  fw::Controller& controller() { return controller_; }
  PlantLink& plant() { return *plant_; }
  void set_plant(std::unique_ptr<PlantLink> plant) { plant_ = std::move(plant); }

  struct Counters {
    std::uint64_t frames_out = 0, frames_dropped = 0, frames_corrupted = 0;
    std::uint64_t holds = 0, hold_timeouts = 0;
  };
  const Counters& counters() const { return counters_; }

 private:
  void tick_once(std::uint64_t wall_us);
  void collect_device_output();
  void frame_done();  // frame_ holds one whole frame
  void deliver(const std::uint8_t* data, std::size_t size, std::uint64_t wall_us);

  fw::Controller controller_;
  std::unique_ptr<PlantLink> plant_;
  SimulationOptions options_;
  std::uint64_t last_wall_us_ = 0;
  std::uint64_t host_wall_us_ = 0;     // wall time of the host's last bytes
  double s_at_rate_ = 0;               // virtual seconds before the last control-rate change
  std::uint64_t ticks_at_rate_ = 0;    // ... and the tick it happened at
  bool contact_line_ = false;
  std::vector<std::uint8_t> frame_;    // device bytes of the frame being cut out
  std::vector<std::uint8_t> out_;      // device bytes ready for the host
  struct Hold {
    bool active = false;
    std::uint64_t since_wall_us = 0;
    std::uint64_t release_tick = 0;    // when the host's reaction is delivered
    bool releasing = false;
    std::vector<std::uint8_t> pending;  // host bytes waiting for release_tick
  } hold_;
  Counters counters_;
};

}  // namespace palp::sim
