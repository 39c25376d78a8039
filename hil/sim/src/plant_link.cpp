// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/plant_link.hpp"

namespace palp::sim {

plant::PlantConfig ModelPlant::config_for(std::uint64_t seed) {
  plant::PlantConfig c;
  c.noise_seed = seed;
  return c;
}

ModelPlant::ModelPlant(const std::string& phantom, std::uint64_t seed)
    : phantom_(phantom),
      plant_(config_for(seed),
             phantom == "none" ? nullptr : plant::load_shipped_phantom(phantom)) {}

std::array<std::uint16_t, 6> ModelPlant::pressure_codes() { return plant_.pressure_adcs(); }

}  // namespace palp::sim
