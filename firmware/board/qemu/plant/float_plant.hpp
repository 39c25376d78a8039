// SPDX-License-Identifier: Apache-2.0
// FloatPlant: the probe and one phantom, in single precision, for the QEMU board to read its
// sensors from (README.md in this directory). A port of the part of hil/plant that one scene
// needs: the coil's electrics (R, L, back-EMF with K_f(s)), the moving coil on its springs with
// viscous damping, the end stops, the exact Sneddon sphere on a bonded layer with its
// Kelvin-Voigt term and participating mass, the sensors. Same equations, same numbers, same
// integrator as hil/plant (its README.md "Equations", "Integrator", "Parameters").
//
// The scene is fixed (README.md "Scene"): phantom solid_1d at its position 3 (x = 27 mm, y = 0),
// the probe vertical, the mount placed so the tip floating at I_c = 0.5 A just touches the flat
// top (z_mount = z_touch - s_f = -25 mm). palp-sim places itself identically with
// `--phantom solid_1d --mount-mm 27 0 -25`.
//
// Float arithmetic, no heap, no exceptions, no RTTI; step() costs a few hundred instructions on
// the Cortex-M4F (README.md "Cost").
#pragma once

#include <array>
#include <cstdint>

namespace palp::qemu {

/// What the board's peripherals read at one tick.
struct PlantSensors {
  float i_sense_A;                              // current sense: 12-bit, +-5 A, with dither noise
  std::uint16_t encoder_timer;                  // quadrature timer count (1 um a count), mod 2^16
  std::array<std::uint16_t, 6> pressure_codes;  // 12-bit codes, index 0 = paper channel 1
  float supply_V;                               // H-bridge supply
};

/// The fixed scene, for whoever must place palp-sim (or hil/plant) the same way.
struct FloatPlantScene {
  static constexpr const char* kPhantom = "solid_1d";  // hil/plant/phantoms/solid_1d.phantom
  static constexpr int kPosition = 3;                  // paper §IV-A: the tuned position
  static constexpr float kMountX_m = 0.027f;           // position 3: 9 mm x 3 (solid_1d.phantom)
  static constexpr float kMountY_m = 0.0f;             // the bar's centre line
  static constexpr float kMountZ_m = -0.025f;          // z_touch (flat top, 0) - s_f (25 mm)
};

class FloatPlant {
 public:
  /// Parked: coil on the rear stop (s = 0, encoder 0), at rest, 0 A; the mount in the scene.
  FloatPlant();

  /// What the board reads at this tick (a pure function of the state and the tick count).
  PlantSensors sensors() const;
  /// Advance one control tick of dt_s (10-100 us) with average coil voltage v_coil_V (PWM duty
  /// times the supply; clamped to +-24 V, NaN counts as 0 V; dt_s <= 0 or NaN: no step).
  void step(float v_coil_V, float dt_s);

  float position_m() const;  ///< stroke coordinate s from the rear stop (true, not quantised)
  float coil_current_A() const { return current_A_; }  ///< true coil current
  float contact_force_N() const { return force_N_; }   ///< on the tip, >= 0, toward -z

  float velocity_m_per_s() const { return velocity_.hi; }
  /// Indentation delta = max(0, s - s_f): the floating tip just touches.
  float indentation_m() const { return x_m_.hi > 0.0f ? x_m_.hi : 0.0f; }
  std::uint32_t tick() const { return tick_; }

 private:
  void update_contact();  // the contact at x_m_ (depth = x in this scene)

  /// A float sum carrying its rounding error (Kahan): increments far below the value's ulp
  /// (a kick of a*dt/2, a drift of v*dt) accumulate as in a double instead of being rounded
  /// away tick after tick (README.md "Agreement": without it the velocity drifts by 2e-5
  /// relative over a 46 ms mechanical time constant). hi is the value; |lo| < ulp(hi)/2.
  struct Compensated {
    float hi = 0.0f, lo = 0.0f;
    void add(float d) {
      const float y = d + lo;
      const float t = hi + y;
      lo = y - (t - hi);
      hi = t;
    }
  };

  // State. The position is kept as x = s - s_f (the float position): x is the indentation
  // itself in this scene, exact at the first touch, and float resolves it to 0.5 nm at 5 mm.
  Compensated x_m_;
  Compensated velocity_;
  float current_A_ = 0.0f;
  std::uint32_t tick_ = 0;

  // Contact after the last step (reused as the next step's start, as hil/plant does).
  float force_N_ = 0.0f;            // total contact force, >= 0
  float rate_free_force_N_ = 0.0f;  // elastic part
  float damping_N_s_per_m_ = 0.0f;  // Kelvin-Voigt tau k_t
  float contact_mass_kg_ = 0.0f;    // participating mass engaged
  bool touching_ = false;

  // K_f at the end of the last step and the per-dt electrical constants.
  float kf_N_per_A_;
  float cached_dt_s_ = -1.0f, elec_decay_ = 0.0f, elec_mean_ = 0.0f;
};

}  // namespace palp::qemu
