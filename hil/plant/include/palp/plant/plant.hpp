// SPDX-License-Identifier: Apache-2.0
// Plant: the probe (coil electrics, moving coil on its springs and slides, end stops, tip) and
// the phantom it touches, advanced one control tick at a time by the simulator.
//
// Per step (README.md "Equations" and "Integrator"):
//   L di/dt = v - R i - K_f(s) ds/dt         exact exponential over the tick (speed frozen)
//   m(delta) d2s/dt2 = K_f(s) i_mean - k_v (s - s_0) - b_v ds/dt + m_v g cos - F_contact
//                                             velocity Verlet, damping by the trapezoidal rule
//                                             (second order; one contact evaluation per step)
//   end stops: inelastic kinematic limits at stroke_min and stroke_max.
// The tip apex sits at mount + s a in the phantom frame, a the probe's axis (default (0, 0, 1));
// the depth along the axis is delta = (z_tip - z_touch) / a_z, where z_touch is the apex's z at
// which the spherical tip moving along the axis first touches the surface (on a slope the sphere
// touches off-axis: sphere_touch / sphere_touch_along in phantom.hpp). z_touch is computed when
// the site (the axis line, named by its crossing of z = 0) changes and the tip is within
// R + 0.5 mm above the surface on the axis (that crossing stands in farther out, where nothing
// touches for slopes up to 60 degrees; an axis off the footprint touches nothing). The contact
// law is taken along the axis at theta to the touched point's normal (README.md "Oblique
// contact": the normal law at delta cos(theta) plus Mindlin's tangential force).
// No allocation per step; sensor reads draw counter-based noise keyed by the tick number.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>

#include "palp/plant/config.hpp"
#include "palp/plant/contact.hpp"
#include "palp/plant/force_constant.hpp"
#include "palp/plant/phantom.hpp"

namespace palp::plant {

/// Mechanical and electrical state, for tests and for placing the coil.
struct CoilState {
  double position_m = 0.0;  // stroke coordinate s
  double velocity_m_per_s = 0.0;
  double current_A = 0.0;
};

class Plant {
 public:
  /// phantom may be null: free air. Throws std::invalid_argument on an unusable config.
  explicit Plant(PlantConfig config, std::shared_ptr<const Phantom> phantom = nullptr);

  // --- placing the probe -------------------------------------------------------------------
  /// Place the mount at once (a teleport: no speed enters the contact's viscous term).
  /// (x, y, z) is the tip apex at stroke origin s = 0 (encoder count 0), phantom frame.
  void set_mount(double x_m, double y_m, double z_m);
  /// Move the mount to (x, y, z) during the next step (the robot's continuous motion: the
  /// change of the surface gap over that step counts as speed in the contact's viscous term).
  void move_mount(double x_m, double y_m, double z_m);
  /// Put the coil in a given state (tests, ring-down); the contact memory is reset.
  void reset_state(const CoilState& state);
  /// The probe's axis (the coil's +stroke direction), a unit vector in the phantom frame with
  /// z > 0; default (0, 0, 1). The mount stays; the site (the axis line through it) is taken
  /// anew, its first touch at the next step. An axis within 1e-12 of (0, 0, 1) is taken as
  /// exactly that. Throws std::invalid_argument unless the
  /// length is 1 within 1e-9 and z > 0.
  void set_probe_axis(const std::array<double, 3>& axis);
  /// cos(angle between gravity and the probe's axis), 1 = pointing down: the coil's weight along
  /// its stroke. The spring preload stays the one set up vertically. Throws for |c| > 1.
  void set_gravity_axis_cosine(double cosine);

  // --- time --------------------------------------------------------------------------------
  /// Advance by dt_s (10-100 us) with average coil voltage v_coil_V (the PWM duty times the
  /// supply; clamped to +-supply, NaN counts as 0 V). Throws std::invalid_argument if dt <= 0.
  void step(double dt_s, double v_coil_V);
  /// Advance by the configured tick period.
  void step(double v_coil_V) { step(config_.tick_period_s, v_coil_V); }

  // --- sensors (what the firmware reads) ----------------------------------------------------
  double coil_current_A() const { return current_A_; }  // true current
  /// Current-sense reading: true current + noise, quantised by the current-sense ADC, A.
  double current_sense_A() const;
  std::uint16_t current_sense_code() const;
  /// Encoder count from the stroke origin (1 count = encoder_resolution_m), round to nearest.
  std::int32_t encoder_count() const;
  /// Pressure ADC code of paper channel 1..6 (code/4096 = 0.5 + 0.4 p / 1245.42 Pa, + noise).
  /// Channels a phantom lacks read 0 Pa. Throws std::out_of_range for other channel numbers.
  std::uint16_t pressure_adc(int channel) const;
  /// The six pressure ADC codes at once (index 0 = paper channel 1), each equal to
  /// pressure_adc(k + 1): the simulator's per-tick read, with the phantom's channels evaluated once.
  std::array<std::uint16_t, kPressureChannels> pressure_adcs() const;

  // --- true state (tests, logging) ----------------------------------------------------------
  double position_m() const { return s_m_; }
  double velocity_m_per_s() const { return v_m_per_s_; }
  /// Contact force on the tip (>= 0, toward -z) at the state after the last step, set_mount or
  /// reset_state (a move_mount takes effect in the next step).
  double contact_force_N() const { return contact_.force_N; }
  double elastic_contact_force_N() const { return contact_.elastic_force_N; }
  double indentation_m() const;  // max(0, delta)
  double tip_z_m() const { return mount_z_m_ + s_m_ * axis_[2]; }
  const std::array<double, 3>& probe_axis() const { return axis_; }
  /// The mount: the tip apex at stroke origin, phantom frame.
  std::array<double, 3> mount_m() const { return {mount_x_m_, mount_y_m_, mount_z_m_}; }
  /// cos(theta) between the probe's axis and the surface normal at the site's first touch
  /// (1: along the normal, and in free air).
  double axis_normal_cosine() const;
  /// The contact force's parts: normal to the surface at the touched point and tangential
  /// (Mindlin / Coulomb); contact_force_N() is their sum along the axis.
  double normal_contact_force_N() const { return contact_.force_N / contact_.axial_per_normal; }
  double tangential_contact_force_N() const {
    return normal_contact_force_N() * contact_.tangential_per_normal;
  }
  /// The force of the material on the tip, phantom frame: -(F_n n + F_t t), n the normal at the
  /// touched point, t the axis's direction in the tangent plane (zero out of contact).
  std::array<double, 3> contact_force_vector_N() const;
  double channel_pressure_Pa(int channel) const;  // true gauge pressure, paper channel 1..6
  /// Where the tip moving along the probe's axis through the mount first touches the phantom:
  /// the contact gap's zero (apex_z_m), the touched point and the surface normal there
  /// (touches = false: free air). The contact law's parameters and the channels are taken where
  /// the axis crosses the surface (the mount's x, y for a vertical probe), not at the point.
  SphereTouch site_touch() const;
  double force_constant_N_per_A() const { return kf_.at(s_m_); }
  bool at_rear_stop() const;
  bool at_front_stop() const;
  double time_s() const { return time_s_; }
  std::uint64_t tick() const { return tick_; }

  /// Spring neutral point s_0 (behind the rear stop: the preload), from the float condition
  /// K_f(s_f) I_c + m g = k_v (s_f - s_0) with the probe vertical.
  double spring_neutral_m() const { return spring_neutral_m_; }
  const PlantConfig& config() const { return config_; }
  const ForceConstantTable& force_constant() const { return kf_; }
  const Phantom* phantom() const { return phantom_.get(); }
  const ContactParams& contact_params() const { return params_; }

 private:
  void refresh_site();
  void ensure_touch();
  double depth_now() const;
  double gap_offset() const;  // depth - s
  void update_contact(double dt_s, double mount_rate_m_per_s);
  std::uint16_t pressure_code(int channel, double pressure_Pa) const;  // + noise, quantised
  std::uint16_t pressure_code_at(double pressure_Pa, double g) const;  // with noise sigma g

  PlantConfig config_;
  ForceConstantTable kf_;
  // K_f at the end of the last step (the next step starts where it ended): {s, K_f(s)}
  double kf_cached_s_m_ = std::numeric_limits<double>::quiet_NaN(), kf_cached_ = 0.0;
  std::shared_ptr<const Phantom> phantom_;
  double spring_neutral_m_ = 0.0;

  // state
  double s_m_ = 0.0, v_m_per_s_ = 0.0, current_A_ = 0.0;
  double time_s_ = 0.0;
  std::uint64_t tick_ = 0;

  // the probe's axis, and the mount and the contact site on that axis
  std::array<double, 3> axis_{0.0, 0.0, 1.0};
  bool vertical_ = true;  // axis_ is exactly (0, 0, 1): the vertical formulas, bit for bit
  double mount_x_m_ = 0.0, mount_y_m_ = 0.0, mount_z_m_ = 0.0;
  double site_x_m_ = 0.0, site_y_m_ = 0.0;  // the axis line's crossing of z = 0
  double cos_theta_ = 1.0;                  // axis . normal at the touch (1: none)
  double surface_z_m_ = 0.0;        // contact zero: z_touch, or the axis's crossing while far
  double apex_surface_z_m_ = 0.0;   // z where the axis crosses the surface (+inf: nothing)
  SphereTouch touch_{};             // valid when touch_valid_
  bool touch_valid_ = false;
  struct SearchedTouch {  // the last site searched with sphere_touch
    bool valid = false;
    double x_m = 0.0, y_m = 0.0;
    SphereTouch touch{};
  } searched_;
  double gap_offset_prev_m_ = 0.0;  // gap_offset() at the end of the previous step
  bool site_dirty_ = true;
  ContactParams params_{};
  ContactModel contact_model_{};
  ContactModel::Output contact_{};

  // noise keys of the sensors' streams (noise.hpp), from config_.noise_seed
  std::uint64_t current_noise_key_ = 0, encoder_noise_key_ = 0;
  std::array<std::uint64_t, kPressureChannels> pressure_noise_keys_{};

  // per-dt constants
  double cached_dt_ = -1.0, elec_decay_ = 0.0, elec_mean_ = 0.0;
};

}  // namespace palp::plant
