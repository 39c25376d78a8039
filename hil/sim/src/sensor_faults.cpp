// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/sensor_faults.hpp"

#include <cstdio>

#include "palp/plant/sensors.hpp"

namespace palp::sim {

std::string SensorFaults::describe() const {
  std::string s;
  auto add = [&](const std::string& what) { s += (s.empty() ? "" : ",") + what; };
  if (encoder_stuck) add("encoder-stuck");
  if (encoder_offset_counts != 0) add("encoder-glitch=" + std::to_string(encoder_offset_counts));
  if (adc == AdcFault::stuck) add("adc-stuck");
  if (adc == AdcFault::saturate_high) add("adc-saturate=high");
  if (adc == AdcFault::saturate_low) add("adc-saturate=low");
  if (driver) add("driver");
  if (supply_V) {
    char v[32];
    std::snprintf(v, sizeof v, "supply-sag=%gV", *supply_V);
    add(v);
  }
  return s.empty() ? "none" : s;
}

FaultyPlant::FaultyPlant(std::unique_ptr<PlantLink> inner, SensorFaults& faults,
                         const plant::SensorConfig& sensors, double supply_nominal_V)
    : inner_(std::move(inner)),
      faults_(faults),
      rail_high_A_(static_cast<float>(plant::current_A_from_code(
          static_cast<std::uint16_t>((1u << sensors.current_sense_bits) - 1u),
          sensors.current_sense_full_scale_A, sensors.current_sense_bits))),
      rail_low_A_(static_cast<float>(plant::current_A_from_code(
          0, sensors.current_sense_full_scale_A, sensors.current_sense_bits))),
      supply_nominal_V_(supply_nominal_V) {}

void FaultyPlant::step(double dt_s, double v_coil_V) {
  double v = v_coil_V;
  if (faults_.driver) v = 0.0;  // outputs off
  else if (faults_.supply_V) v *= *faults_.supply_V / supply_nominal_V_;
  inner_->step(dt_s, v);
}

float FaultyPlant::current_sense_A() {
  switch (faults_.adc) {
    case AdcFault::saturate_high: return rail_high_A_;
    case AdcFault::saturate_low: return rail_low_A_;
    case AdcFault::stuck:
      if (!faults_.frozen_sense_A) faults_.frozen_sense_A = inner_->current_sense_A();
      return *faults_.frozen_sense_A;
    case AdcFault::none: break;
  }
  return inner_->current_sense_A();
}

std::int32_t FaultyPlant::encoder_counts() {
  const std::int32_t counts = inner_->encoder_counts() + faults_.encoder_offset_counts;
  if (!faults_.encoder_stuck) return counts;
  if (!faults_.frozen_counts) faults_.frozen_counts = counts;
  return *faults_.frozen_counts;
}

float FaultyPlant::supply_V() {
  return faults_.supply_V ? static_cast<float>(*faults_.supply_V) : inner_->supply_V();
}

}  // namespace palp::sim
