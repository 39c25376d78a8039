// SPDX-License-Identifier: Apache-2.0
// The physical model (hil/plant) as the simulation's PlantLink: the sensors a board would read.
#pragma once

#include <memory>
#include <string>

#include "palp/plant/plant.hpp"
#include "palp/sim/simulation.hpp"

namespace palp::sim {

class ModelPlant final : public PlantLink {
 public:
  /// phantom: a shipped phantom name ("solid_1d", "pad_2d", ...) or "none" for free air.
  /// Throws plant::PhantomError for an unknown or malformed phantom.
  ModelPlant(const std::string& phantom, std::uint64_t seed);

  void step(double dt_s, double v_coil_V) override { plant_.step(dt_s, v_coil_V); }
  float current_sense_A() override { return static_cast<float>(plant_.current_sense_A()); }
  std::int32_t encoder_counts() override { return plant_.encoder_count(); }
  std::array<std::uint16_t, 6> pressure_codes() override;
  float supply_V() override { return static_cast<float>(plant_.config().coil.supply_V); }

  plant::Plant& model() { return plant_; }
  const std::string& phantom_name() const { return phantom_; }

 private:
  static plant::PlantConfig config_for(std::uint64_t seed);
  std::string phantom_;
  plant::Plant plant_;
};

}  // namespace palp::sim
