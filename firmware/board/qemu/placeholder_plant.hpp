// A stand-in for the float plant (plant/float_plant.hpp, contract 1 of issue 18) until that
// lands: the same API, with the coil's electrics only (R = 5.8 ohm, L = 2.07 mH, exact over a
// tick), the coil at rest at the stroke origin, zero pressure and a 24 V supply.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace palp::qemu {

struct PlantSensors {
  float i_sense_A;
  std::uint16_t encoder_timer;
  std::array<std::uint16_t, 6> pressure_codes;
  float supply_V;
};

class FloatPlant {
 public:
  FloatPlant() = default;
  PlantSensors sensors() const {
    PlantSensors s{};
    s.i_sense_A = i_A_;
    s.encoder_timer = 0;
    s.pressure_codes.fill(2048);  // code/4096 = 0.5 at 0 Pa (core/README.md, pressure)
    s.supply_V = 24.0f;
    return s;
  }
  void step(float v_coil_V, float dt_s) {
    const float a = std::exp(-kR_ohm * dt_s / kL_H);
    i_A_ = i_A_ * a + v_coil_V * ((1.0f - a) / kR_ohm);
  }
  float position_m() const { return 0.0f; }
  float coil_current_A() const { return i_A_; }
  float contact_force_N() const { return 0.0f; }

 private:
  static constexpr float kR_ohm = 5.8f;
  static constexpr float kL_H = 2.07e-3f;
  float i_A_ = 0.0f;
};

}  // namespace palp::qemu
