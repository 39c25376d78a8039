// SPDX-License-Identifier: Apache-2.0
// Sensor and actuator faults in palp-sim (the control channel's `fault ...` commands): what a
// broken encoder, current-sense ADC, H-bridge driver or supply does to the readings the board
// takes and to the voltage the coil gets. FaultyPlant wraps the simulation's PlantLink and applies
// the SensorFaults the Instrument keeps (so they survive a `phantom` or `seed` rebuild); the
// firmware core's reaction is in firmware/core/include/palp/fw/sensor_monitor.hpp and
// docs/reliability.md section 5.
//
//   encoder stuck       the count freezes at its value when the fault begins
//   encoder glitch      miscounted edges: the count is offset by n from the next tick on (glitches
//                       add up; the true position is unchanged)
//   ADC stuck           the current-sense reading freezes at its value when the fault begins
//   ADC saturated       the current-sense ADC reads its top (or bottom) code: +4.9976 A (-5 A)
//   driver fault        the H-bridge driver asserts its fault line and turns its outputs off: the
//                       coil sees 0 V (its current decays with L/R = 0.36 ms)
//   supply sag          the bridge supply reads <V> and the coil gets the commanded voltage times
//                       <V> / the nominal supply (the PWM duty was computed for the nominal one)
// clear() ends them all: the readings are the plant's again (a stuck or glitched encoder jumps
// back to the true count).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "palp/plant/config.hpp"
#include "palp/sim/simulation.hpp"

namespace palp::sim {

enum class AdcFault : std::uint8_t { none, stuck, saturate_high, saturate_low };

struct SensorFaults {
  bool encoder_stuck = false;
  std::int32_t encoder_offset_counts = 0;
  AdcFault adc = AdcFault::none;
  bool driver = false;
  std::optional<double> supply_V;  ///< the sagged supply; nullopt: nominal

  // the frozen readings, taken at the first read after the fault began
  std::optional<std::int32_t> frozen_counts;
  std::optional<float> frozen_sense_A;

  void clear() { *this = SensorFaults{}; }
  /// "none" or the faults on, comma-separated ("encoder-stuck,supply-sag=17V").
  std::string describe() const;
};

class FaultyPlant final : public PlantLink {
 public:
  /// sensors: the plant's sensor chain (the current-sense ADC's rails); supply_nominal_V: its
  /// bridge supply.
  FaultyPlant(std::unique_ptr<PlantLink> inner, SensorFaults& faults,
              const plant::SensorConfig& sensors, double supply_nominal_V);

  void step(double dt_s, double v_coil_V) override;
  float current_sense_A() override;
  std::int32_t encoder_counts() override;
  std::array<std::uint16_t, 6> pressure_codes() override { return inner_->pressure_codes(); }
  float supply_V() override;
  bool driver_fault() override { return faults_.driver || inner_->driver_fault(); }

  PlantLink& inner() { return *inner_; }

 private:
  std::unique_ptr<PlantLink> inner_;
  SensorFaults& faults_;
  float rail_high_A_, rail_low_A_;
  double supply_nominal_V_;
};

}  // namespace palp::sim
