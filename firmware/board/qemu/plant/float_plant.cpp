// SPDX-License-Identifier: Apache-2.0
// FloatPlant: hil/plant's Plant::step for the fixed scene, in float (README.md "Model").
#include "float_plant.hpp"

#include <cmath>

#include "contact_law.hpp"

namespace palp::qemu {
namespace {

// ---- coil (hil/plant PlantConfig::coil, paper §II-A) --------------------------------------
constexpr float kResistance_ohm = 5.8f;    // §II-A, measured on the integrated actuator
constexpr float kInductance_H = 2.07e-3f;  // §II-A
constexpr float kSupply_V = 24.0f;         // issue: the H-bridge supply
constexpr float kElecTau_s = kInductance_H / kResistance_ohm;  // L / R = 0.357 ms

// K_f(s): hil/plant default_kf_table(), piecewise linear, constant beyond the ends.
constexpr float kKfRear = 3.30f;   // s = 0: assumed (rear end, only reached when parked)
constexpr float kKfMid = 3.84f;    // s = 17 mm: §II-A, near mid-stroke
constexpr float kKfWork = 2.918f;  // s >= 23.5 mm: §II-A "2.918 N/A at 24 mm travel", flat
constexpr float kKfMid_m = 0.017f;
constexpr float kKfFlat_m = 0.0235f;

// ---- mechanics (hil/plant PlantConfig::mechanics; §II-A, §IV-A, §IV-B) --------------------
constexpr float kMovingMass_kg = 0.161f;      // §IV-B
constexpr float kDamping_N_s_per_m = 1.38f;   // §IV-B (slide friction folded in, hil README)
constexpr float kSpringRate_N_per_m = 43.9f;  // §II-A
constexpr float kFloatCurrent_A = 0.5f;       // §IV-A: contact threshold I_c
constexpr float kFloatPosition_m = 0.025f;    // assumed s_f (hil README "Frames and stroke")
constexpr float kStrokeMax_m = 0.034f;        // assumed stroke (front stop)
// The springs' preload is set with the probe vertical so the coil floats at s_f at I_c:
// k_v (s_f - s_0) = K_f(s_f) I_c + m_v g. Springs plus the coil's weight then push
// -k_v x - K_f(s_f) I_c at x = s - s_f: gravity cancels exactly (the phantom carries the
// participating mass's weight, as in hil/plant).
constexpr float kHoldForce_N = kKfWork * kFloatCurrent_A;          // 1.459 N, the paper's F_0
constexpr float kStopRear_x_m = -kFloatPosition_m;                 // s = 0
constexpr float kStopFront_x_m = kStrokeMax_m - kFloatPosition_m;  // s = 34 mm

// ---- sensors (hil/plant SensorConfig; sensors.cpp) ----------------------------------------
constexpr float kCountsPerMetre = 1e6f;      // §II-A: 1 um a count
constexpr float kFloatCounts = 25000.0f;     // s_f in counts
constexpr float kCurrentFullScale_A = 5.0f;  // assumed +-5 A, 12 bit, 0 A at code 2048
constexpr float kCurrentHalfCodes = 2048.0f;
constexpr float kCurrentTopCode = 4095.0f;
// Dither: triangular on [-a, a] with a = sqrt(6) x 2 mA, the rms of hil/plant's Gaussian
// current-sense noise (2 mA, assumed there), from a hash of the tick (README "Sensors").
constexpr float kDitherHalfWidth_A = 2.449489743f * 2e-3f;
// A solid_1d has no air channels: every channel reads 0 Pa gauge, code 4096 x 0.5 (ELVH-L05D,
// code/4096 = 0.5 + 0.4 p / 1245.42 Pa; hil/plant sensors.cpp). Its 1 Pa noise is left out.
constexpr std::uint16_t kZeroPressureCode = 2048;

float force_constant(float x_m) {
  const float s = x_m + kFloatPosition_m;
  if (s >= kKfFlat_m) return kKfWork;
  if (s <= 0.0f) return kKfRear;
  if (s <= kKfMid_m) return kKfRear + (kKfMid - kKfRear) * (s / kKfMid_m);
  return kKfMid + (kKfWork - kKfMid) * ((s - kKfMid_m) / (kKfFlat_m - kKfMid_m));
}

// MurmurHash3's 32-bit finaliser (Appleby): every input bit reaches every output bit.
std::uint32_t mix32(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

}  // namespace

FloatPlant::FloatPlant() : x_m_{kStopRear_x_m, 0.0f}, kf_N_per_A_(force_constant(kStopRear_x_m)) {}

float FloatPlant::position_m() const { return x_m_.hi + kFloatPosition_m; }

// Kelvin-Voigt has no memory (solid_1d has no standard-linear-solid term): a pure function of x.
void FloatPlant::update_contact() {
  const float x = x_m_.hi;
  touching_ = x > 0.0f;
  if (!touching_) {
    rate_free_force_N_ = damping_N_s_per_m_ = contact_mass_kg_ = force_N_ = 0.0f;
    return;
  }
  const ContactPoint el = contact_elastic(x);
  rate_free_force_N_ = el.force_N;
  damping_N_s_per_m_ = ContactConstants::kRetardationTime_s * el.stiffness_N_per_m;
  const float engage =
      x < ContactConstants::kMassEngageDepth_m ? x / ContactConstants::kMassEngageDepth_m : 1.0f;
  contact_mass_kg_ = ContactConstants::kParticipatingMass_kg * engage;
}

void FloatPlant::step(float v_coil_V, float dt_s) {
  if (!(dt_s > 0.0f)) return;
  float v = v_coil_V;
  if (v != v) v = 0.0f;
  if (v > kSupply_V) v = kSupply_V;
  if (v < -kSupply_V) v = -kSupply_V;
  if (dt_s != cached_dt_s_) {
    cached_dt_s_ = dt_s;
    elec_decay_ = std::exp(-dt_s / kElecTau_s);
    elec_mean_ = -std::expm1(-dt_s / kElecTau_s) * (kElecTau_s / dt_s);
  }

  // Electrics: exact over the tick with the speed held; the mechanics takes the mean current.
  const float i_inf = (v - kf_N_per_A_ * velocity_.hi) * (1.0f / kResistance_ohm);
  const float i_new = i_inf + (current_A_ - i_inf) * elec_decay_;
  const float i_mean = i_inf + (current_A_ - i_inf) * elec_mean_;
  auto other_force = [&](float x, float kf) {  // coil, springs, gravity
    return kf * i_mean - kSpringRate_N_per_m * x - kHoldForce_N;
  };
  const float half = 0.5f * dt_s;

  // Velocity Verlet: half kick with the forces at the start (the contact from the last step).
  const float v0 = velocity_.hi;
  velocity_.add(half * (other_force(x_m_.hi, kf_N_per_A_) - kDamping_N_s_per_m * v0 - force_N_) /
                (kMovingMass_kg + contact_mass_kg_));
  // Drift, inelastic end stops.
  x_m_.add(dt_s * velocity_.hi);
  int stop = 0;
  if (x_m_.hi <= kStopRear_x_m) {
    x_m_ = {kStopRear_x_m, 0.0f};
    stop = -1;
  } else if (x_m_.hi >= kStopFront_x_m) {
    x_m_ = {kStopFront_x_m, 0.0f};
    stop = 1;
  }
  if (static_cast<float>(stop) * velocity_.hi > 0.0f) velocity_ = {};
  const float x = x_m_.hi, vel = velocity_.hi;

  // Contact at the new position; the second half kick implicit in the linear damping
  // (trapezoidal), springs and contact explicit: hil/plant Plant::step, written as the
  // increment of the velocity so that the compensated sum keeps it.
  update_contact();
  const float mass = kMovingMass_kg + contact_mass_kg_;
  kf_N_per_A_ = force_constant(x);
  const float f_other = other_force(x, kf_N_per_A_);
  float kick = half * (f_other - kDamping_N_s_per_m * vel) / mass /
               (1.0f + half * kDamping_N_s_per_m / mass);
  force_N_ = 0.0f;
  if (touching_) {
    const float cd = damping_N_s_per_m_;
    const float kick_contact = half *
                               (f_other - rate_free_force_N_ - (kDamping_N_s_per_m + cd) * vel) /
                               mass / (1.0f + half * (kDamping_N_s_per_m + cd) / mass);
    const float force = rate_free_force_N_ + cd * (vel + kick_contact);
    if (force > 0.0f) {
      kick = kick_contact;
      force_N_ = force;
    }  // else the surface cannot follow: the tip separates
  }
  velocity_.add(kick);
  if (static_cast<float>(stop) * velocity_.hi > 0.0f) velocity_ = {};

  current_A_ = i_new;
  ++tick_;
}

PlantSensors FloatPlant::sensors() const {
  PlantSensors out{};
  // Encoder: round(s / 1 um); s >= 0, so adding 0.5 and truncating rounds to nearest.
  const float counts = x_m_.hi * kCountsPerMetre + kFloatCounts;
  const std::int32_t count = counts > 0.0f ? static_cast<std::int32_t>(counts + 0.5f) : 0;
  out.encoder_timer = static_cast<std::uint16_t>(count);  // the timer wraps mod 2^16

  // Current sense: true current + dither, 12-bit code (rounded, clamped), back to amperes.
  const std::uint32_t r = mix32(tick_ * 0x9e3779b9u + 0x2545f491u);
  const float tri =
      static_cast<float>(static_cast<std::int32_t>((r & 0xffffu) + (r >> 16)) - 65535) *
      (1.0f / 65536.0f);  // triangular on (-1, 1)
  const float i = current_A_ + kDitherHalfWidth_A * tri;
  float code = kCurrentHalfCodes + i * (kCurrentHalfCodes / kCurrentFullScale_A) + 0.5f;
  code = code < 0.0f ? 0.0f : code;
  code = static_cast<float>(static_cast<std::int32_t>(code));
  code = code > kCurrentTopCode ? kCurrentTopCode : code;
  out.i_sense_A = (code - kCurrentHalfCodes) * (kCurrentFullScale_A / kCurrentHalfCodes);

  out.pressure_codes.fill(kZeroPressureCode);
  out.supply_V = kSupply_V;
  return out;
}

}  // namespace palp::qemu
