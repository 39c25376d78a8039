// SPDX-License-Identifier: Apache-2.0
// PlantConfig: every number of the probe model (coil, mechanics, sensors, noise), with the
// paper's values as defaults and the source of each in a comment. SI units throughout.
//
// Stroke geometry (README.md "Stroke"): the stroke coordinate s is the tip's travel from the rear
// end stop (coil fully retracted), positive toward +z (into the specimen). s = 0 is the stroke
// origin and encoder count 0: the coil parks there at zero current, where an incremental encoder
// is zeroed at power-up.
#pragma once

#include <cstdint>
#include <vector>

namespace palp::plant {

/// One point of the force-constant table: K_f at stroke coordinate s.
struct KfPoint {
  double stroke_m;
  double kf_N_per_A;
};

/// The table the model uses by default (piecewise linear in s, constant beyond the end points):
///   s =  0 mm  3.30 N/A  (assumed: rear end of the stroke, only reached when parked)
///   s = 17 mm  3.84 N/A  (paper §II-A: nominal force constant near mid-stroke of a 34 mm stroke)
///   s = 23.5 mm 2.918 N/A (paper §II-A: "reduces to approximately 2.918 N/A at 24 mm travel")
///   s = 34 mm  2.918 N/A (simplification: flat over the whole working range, see README)
std::vector<KfPoint> default_kf_table();

/// Thorlabs VC250 coil on an H-bridge (paper §II-A).
struct CoilConfig {
  double resistance_ohm = 5.8;    // §II-A: measured on the integrated actuator
  double inductance_H = 2.07e-3;  // §II-A
  double supply_V = 24.0;         // issue: 24 V bridge supply; the PWM is its average voltage
  std::vector<KfPoint> kf_table = default_kf_table();
};

/// Moving coil, return springs, end stops, tip (paper §II-A, §IV-B).
struct MechanicsConfig {
  double moving_mass_kg = 0.161;      // §IV-B: identified 161 g, equal to the weighed mass
  double damping_N_s_per_m = 1.38;    // §IV-B: b_v from free-air zeta = 0.2595
  double spring_rate_N_per_m = 43.9;  // §II-A: k_v = 0.0439 N/mm (both springs together)
  double float_current_A = 0.5;       // §IV-A: contact threshold current I_c
  double float_position_m = 0.025;    // assumed: the coil floats at s = 25 mm at I_c (the
                                      // spring preload is derived from this, see README)
  double stroke_min_m = 0.0;          // rear end stop = stroke origin (encoder count 0)
  double stroke_max_m = 0.034;        // front end stop: assumed 34 mm stroke
  double gravity_m_per_s2 = 9.80665;  // standard gravity
  double gravity_axis_cosine = 1.0;   // cos(angle between gravity and the probe's axis, +s);
                                      // 1 = probe points down (Plant::set_gravity_axis_cosine)
  double tip_radius_m = 2.5e-3;       // §II-A: PLA hemisphere, R = 2.5 mm
};

/// Sensors the firmware reads (paper §II-A, §V-A; the board's current-sense chain is assumed).
struct SensorConfig {
  double encoder_resolution_m = 1e-6;       // §II-A: POSIC ID1102L, 1 um per count
  double encoder_noise_m = 0.0;             // optional Gaussian jitter before quantisation
  double current_sense_full_scale_A = 5.0;  // assumed: +-5 A over the ADC range, 0 A mid-scale
  int current_sense_bits = 12;              // STM32G474 ADC
  double current_sense_noise_A = 2e-3;      // assumed: 2 mA rms at the sample
  int pressure_adc_bits = 12;               // STM32G474 ADC
  double pressure_full_scale_Pa = 1245.42;  // §V-A: ELVH-L05D, +-5 inH2O
  double pressure_noise_Pa = 1.0;           // assumed: 1 Pa rms (0.08 % FS)
};

/// Everything a Plant needs besides the phantom.
struct PlantConfig {
  CoilConfig coil;
  MechanicsConfig mechanics;
  SensorConfig sensors;
  std::uint64_t noise_seed = 1;  // same seed, same calls: same noise (counter-based, README)
  double tick_period_s = 50e-6;  // 20 kHz control tick; step(dt, v) may use any dt in 10-100 us
};

}  // namespace palp::plant
