// SPDX-License-Identifier: Apache-2.0
// Plant: coil electrics, moving-coil mechanics, end stops, contact and sensors, one tick a step.
#include "palp/plant/plant.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "palp/plant/noise.hpp"
#include "palp/plant/sensors.hpp"

namespace palp::plant {
namespace {

// The mount starts 1 m above the datum: out of reach of any phantom until it is placed.
constexpr double kParkedMountZ_m = -1.0;
// Beyond R + this above the surface under the apex the sphere's first touch is not searched
// (it lies R (1 / cos(theta) - 1) above z_s on a slope theta: within R for slopes up to 60
// degrees), so lateral travel above the surface costs no search per tick.
constexpr double kTouchMargin_m = 0.5e-3;
// Within this distance of the last searched site the touch is moved along the tangent plane
// instead of searched again (~4 us a search).
constexpr double kTouchReuse_m = 1e-6;

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("PlantConfig: ") + what);
}

}  // namespace

Plant::Plant(PlantConfig config, std::shared_ptr<const Phantom> phantom)
    : config_(std::move(config)), kf_(config_.coil.kf_table), phantom_(std::move(phantom)) {
  const CoilConfig& c = config_.coil;
  const MechanicsConfig& m = config_.mechanics;
  const SensorConfig& s = config_.sensors;
  require(c.resistance_ohm > 0.0 && c.inductance_H > 0.0, "coil R and L must be positive");
  require(c.supply_V > 0.0, "supply voltage must be positive");
  require(m.moving_mass_kg > 0.0 && m.spring_rate_N_per_m > 0.0 && m.damping_N_s_per_m >= 0.0,
          "mass and spring rate must be positive, damping non-negative");
  require(m.stroke_max_m > m.stroke_min_m, "stroke_max must exceed stroke_min");
  require(m.float_position_m > m.stroke_min_m && m.float_position_m < m.stroke_max_m,
          "float position must lie inside the stroke");
  require(m.tip_radius_m > 0.0, "tip radius must be positive");
  require(s.encoder_resolution_m > 0.0, "encoder resolution must be positive");
  require(s.current_sense_bits >= 2 && s.current_sense_bits <= 16 && s.pressure_adc_bits >= 2 &&
              s.pressure_adc_bits <= 16,
          "ADC bits must be 2..16");
  require(s.current_sense_full_scale_A > 0.0 && s.pressure_full_scale_Pa > 0.0,
          "sensor full scales must be positive");
  require(config_.tick_period_s > 0.0, "tick period must be positive");

  // Preload: the springs are set up with the probe vertical, so that at I_c the coil floats
  // at s_f: K_f(s_f) I_c + m g = k_v (s_f - s_0).
  const double hold_N =
      kf_.at(m.float_position_m) * m.float_current_A + m.moving_mass_kg * m.gravity_m_per_s2;
  spring_neutral_m_ = m.float_position_m - hold_N / m.spring_rate_N_per_m;

  const std::uint64_t seed = config_.noise_seed;
  current_noise_key_ = noise_key(seed, static_cast<std::uint32_t>(NoiseStream::current_sense));
  encoder_noise_key_ = noise_key(seed, static_cast<std::uint32_t>(NoiseStream::encoder));
  for (std::size_t k = 0; k < kPressureChannels; ++k) {
    pressure_noise_keys_[k] = noise_key(
        seed, static_cast<std::uint32_t>(NoiseStream::pressure_base) + static_cast<std::uint32_t>(k + 1));
  }

  s_m_ = m.stroke_min_m;  // parked on the rear stop, 0 A
  set_mount(0.0, 0.0, kParkedMountZ_m);
}

void Plant::refresh_site() {
  if (phantom_ && vertical_) {
    apex_surface_z_m_ = phantom_->surface_z_m(site_x_m_, site_y_m_);
    params_ = phantom_->contact_params(site_x_m_, site_y_m_);
    params_.friction_coefficient = phantom_->friction_coefficient();
  } else if (phantom_) {
    // the law where the axis crosses the surface
    const double t = surface_along_axis_m(*phantom_, site_x_m_, site_y_m_, axis_);
    apex_surface_z_m_ = t * axis_[2];
    params_ = std::isfinite(t) ? phantom_->contact_params(site_x_m_ + t * axis_[0],
                                                          site_y_m_ + t * axis_[1])
                               : phantom_->contact_params(site_x_m_, site_y_m_);
    params_.friction_coefficient = phantom_->friction_coefficient();
  } else {
    apex_surface_z_m_ = std::numeric_limits<double>::infinity();
    params_ = ContactParams{};
  }
  surface_z_m_ = apex_surface_z_m_;
  touch_valid_ = false;
  cos_theta_ = 1.0;
}

void Plant::ensure_touch() {
  if (touch_valid_ || !phantom_ || !std::isfinite(apex_surface_z_m_)) return;
  const double r = config_.mechanics.tip_radius_m;
  if (tip_z_m() < apex_surface_z_m_ - r - kTouchMargin_m) return;  // far above
  const double dx = site_x_m_ - searched_.x_m, dy = site_y_m_ - searched_.y_m;
  if (searched_.valid && std::hypot(dx, dy) < kTouchReuse_m) {
    // A sub-micrometre move (the arm's rounding jitter, a slow slide): the touch moves with the
    // surface's tangent plane at the touched point. Vertical: z += -(n_x dx + n_y dy) / n_z; along
    // a tilted axis the line moves by d = (dx, dy, 0) and the touch by d + lambda a, lambda =
    // -(n . d) / (n . a). The error is curvature x d^2 / 2 < 1e-10 m.
    touch_ = searched_.touch;
    const auto& n = touch_.normal;
    double px = dx, py = dy, dz = 0.0;
    if (vertical_) {
      dz = -(n[0] * dx + n[1] * dy) / n[2];
    } else {
      const double lambda = -(n[0] * dx + n[1] * dy) /
                            (n[0] * axis_[0] + n[1] * axis_[1] + n[2] * axis_[2]);
      px += lambda * axis_[0];
      py += lambda * axis_[1];
      dz = lambda * axis_[2];
    }
    touch_.apex_z_m += dz;
    touch_.point_x_m += px;
    touch_.point_y_m += py;
    touch_.point_z_m += dz;
  } else {
    touch_ = vertical_ ? sphere_touch(*phantom_, site_x_m_, site_y_m_, r)
                       : sphere_touch_along(*phantom_, site_x_m_, site_y_m_, axis_, r);
    searched_ = {touch_.touches, site_x_m_, site_y_m_, touch_};
  }
  touch_valid_ = true;
  surface_z_m_ = touch_.apex_z_m;
  const auto& n = touch_.normal;
  cos_theta_ = touch_.touches
                   ? std::clamp(axis_[0] * n[0] + axis_[1] * n[1] + axis_[2] * n[2], 0.0, 1.0)
                   : 1.0;
}

double Plant::axis_normal_cosine() const {
  if (touch_valid_) return cos_theta_;
  const SphereTouch t = site_touch();
  if (!t.touches) return 1.0;
  return std::clamp(axis_[0] * t.normal[0] + axis_[1] * t.normal[1] + axis_[2] * t.normal[2],
                    0.0, 1.0);
}

std::array<double, 3> Plant::contact_force_vector_N() const {
  std::array<double, 3> f{0.0, 0.0, 0.0};
  if (!(contact_.force_N > 0.0) || !touch_valid_) return f;
  const double fn = normal_contact_force_N(), ft = tangential_contact_force_N();
  const auto& n = touch_.normal;
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta_ * cos_theta_));
  for (int i = 0; i < 3; ++i) {
    const double t = sin_theta > 0.0 ? (axis_[i] - n[i] * cos_theta_) / sin_theta : 0.0;
    f[i] = -(fn * n[i] + ft * t);
  }
  return f;
}

void Plant::set_probe_axis(const std::array<double, 3>& axis) {
  const double norm = std::hypot(axis[0], axis[1], axis[2]);
  if (!(std::abs(norm - 1.0) <= 1e-9) || !(axis[2] > 0.0)) {
    throw std::invalid_argument(
        "Plant::set_probe_axis: the axis must be a unit vector with z > 0");
  }
  std::array<double, 3> a = {axis[0] / norm, axis[1] / norm, axis[2] / norm};
  if (std::hypot(a[0], a[1]) < 1e-12) a = {0.0, 0.0, 1.0};
  if (a == axis_) return;
  axis_ = a;
  vertical_ = a[0] == 0.0 && a[1] == 0.0 && a[2] == 1.0;
  site_dirty_ = true;
  searched_.valid = false;
  move_mount(mount_x_m_, mount_y_m_, mount_z_m_);  // the site on the new axis line
}

void Plant::set_gravity_axis_cosine(double cosine) {
  if (!(std::abs(cosine) <= 1.0)) {
    throw std::invalid_argument("Plant::set_gravity_axis_cosine: a cosine lies in [-1, 1]");
  }
  config_.mechanics.gravity_axis_cosine = cosine;
}

SphereTouch Plant::site_touch() const {
  if (touch_valid_) return touch_;
  if (!phantom_) return SphereTouch{false, std::numeric_limits<double>::infinity()};
  const double r = config_.mechanics.tip_radius_m;
  return vertical_ ? sphere_touch(*phantom_, site_x_m_, site_y_m_, r)
                   : sphere_touch_along(*phantom_, site_x_m_, site_y_m_, axis_, r);
}

void Plant::set_mount(double x_m, double y_m, double z_m) {
  move_mount(x_m, y_m, z_m);
  ensure_touch();
  gap_offset_prev_m_ = gap_offset();
  update_contact(0.0, 0.0);  // the tip now sits at the new depth, with no speed from the move
}

void Plant::move_mount(double x_m, double y_m, double z_m) {
  // the site is the axis line, named by its crossing of z = 0 (the mount's x, y when vertical)
  const double sx = vertical_ ? x_m : x_m - z_m / axis_[2] * axis_[0];
  const double sy = vertical_ ? y_m : y_m - z_m / axis_[2] * axis_[1];
  mount_x_m_ = x_m;
  mount_y_m_ = y_m;
  if (sx != site_x_m_ || sy != site_y_m_ || site_dirty_) {
    site_x_m_ = sx;
    site_y_m_ = sy;
    refresh_site();
    site_dirty_ = false;
  }
  mount_z_m_ = z_m;
}

void Plant::reset_state(const CoilState& state) {
  const MechanicsConfig& m = config_.mechanics;
  s_m_ = std::clamp(state.position_m, m.stroke_min_m, m.stroke_max_m);
  v_m_per_s_ = state.velocity_m_per_s;
  current_A_ = state.current_A;
  contact_model_.reset();
  ensure_touch();
  gap_offset_prev_m_ = gap_offset();
  update_contact(0.0, 0.0);
}

double Plant::depth_now() const {
  if (vertical_) return mount_z_m_ + s_m_ - surface_z_m_;
  return (tip_z_m() - surface_z_m_) / axis_[2];
}

double Plant::gap_offset() const {
  if (vertical_) return mount_z_m_ - surface_z_m_;
  return (mount_z_m_ - surface_z_m_) / axis_[2];
}

double Plant::indentation_m() const { return std::max(0.0, depth_now()); }

void Plant::update_contact(double dt_s, double mount_rate_m_per_s) {
  contact_ = contact_model_.evaluate(params_, config_.mechanics.tip_radius_m, depth_now(),
                                     v_m_per_s_ + mount_rate_m_per_s, dt_s, cos_theta_);
}

void Plant::step(double dt_s, double v_coil_V) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("Plant::step: dt must be positive");
  const CoilConfig& c = config_.coil;
  const MechanicsConfig& m = config_.mechanics;

  const double v = std::isnan(v_coil_V) ? 0.0 : std::clamp(v_coil_V, -c.supply_V, c.supply_V);
  if (dt_s != cached_dt_) {
    const double tau_e = c.inductance_H / c.resistance_ohm;
    cached_dt_ = dt_s;
    elec_decay_ = std::exp(-dt_s / tau_e);
    elec_mean_ = (1.0 - elec_decay_) * tau_e / dt_s;
  }

  // Electrics: exact solution of L di/dt = v - R i - K_f ds/dt with the speed held over the tick;
  // the mechanics uses the tick's mean current, so the coil's impulse is exact.
  const double kf0 = s_m_ == kf_cached_s_m_ ? kf_cached_ : kf_.at(s_m_);
  const double i_inf = (v - kf0 * v_m_per_s_) / c.resistance_ohm;
  const double i_new = i_inf + (current_A_ - i_inf) * elec_decay_;
  const double i_mean = i_inf + (current_A_ - i_inf) * elec_mean_;

  const double weight = m.moving_mass_kg * m.gravity_m_per_s2 * m.gravity_axis_cosine;
  auto other_force = [&](double s, double kf) {  // coil, springs, gravity
    return kf * i_mean - m.spring_rate_N_per_m * (s - spring_neutral_m_) + weight;
  };
  const double half = 0.5 * dt_s;

  // Velocity Verlet. First half kick with the forces at the start (contact from the last step).
  double vel = v_m_per_s_ +
               half *
                   (other_force(s_m_, kf0) - m.damping_N_s_per_m * v_m_per_s_ - contact_.force_N) /
                   (m.moving_mass_kg + contact_.mass_kg);
  // Drift, with inelastic kinematic end stops.
  double s = s_m_ + dt_s * vel;
  int stop = 0;
  if (s <= m.stroke_min_m) {
    s = m.stroke_min_m;
    stop = -1;
  } else if (s >= m.stroke_max_m) {
    s = m.stroke_max_m;
    stop = 1;
  }
  if (stop * vel > 0.0) vel = 0.0;
  s_m_ = s;

  // Contact at the end of the step; the mount's motion over the step counts as speed.
  ensure_touch();
  const double offset = gap_offset();
  double mount_rate = 0.0;
  if (std::isfinite(offset) && std::isfinite(gap_offset_prev_m_)) {
    mount_rate = (offset - gap_offset_prev_m_) / dt_s;
  }
  gap_offset_prev_m_ = offset;
  v_m_per_s_ = vel;  // provisional: the contact's rate term is settled below
  update_contact(dt_s, mount_rate);

  // Second half kick, implicit in the linear damping (b_v and the contact's tau k_t): with the
  // explicit first half this is the trapezoidal rule for the damping (second order, A-stable);
  // springs and contact stay explicit (stable for omega dt < 2; here omega dt < 0.02).
  const double mass = m.moving_mass_kg + contact_.mass_kg;
  kf_cached_s_m_ = s;
  kf_cached_ = kf_.at(s);
  const double f_other = other_force(s, kf_cached_);
  double vel_end = (vel + half * f_other / mass) / (1.0 + half * m.damping_N_s_per_m / mass);
  if (contact_.touching) {
    const double cd = contact_.damping_N_s_per_m;
    const double with_contact =
        (vel + half * (f_other - contact_.rate_free_force_N - cd * mount_rate) / mass) /
        (1.0 + half * (m.damping_N_s_per_m + cd) / mass);
    const double force = contact_.rate_free_force_N + cd * (with_contact + mount_rate);
    if (force > 0.0) {
      vel_end = with_contact;
      contact_.force_N = force;
    } else {
      contact_.force_N = 0.0;  // the surface cannot follow: the tip separates
    }
  }
  if (stop * vel_end > 0.0) vel_end = 0.0;

  v_m_per_s_ = vel_end;
  current_A_ = i_new;
  time_s_ += dt_s;
  ++tick_;
}

bool Plant::at_rear_stop() const { return s_m_ <= config_.mechanics.stroke_min_m; }
bool Plant::at_front_stop() const { return s_m_ >= config_.mechanics.stroke_max_m; }

double Plant::current_sense_A() const {
  return current_A_from_code(current_sense_code(), config_.sensors.current_sense_full_scale_A,
                             config_.sensors.current_sense_bits);
}

std::uint16_t Plant::current_sense_code() const {
  const SensorConfig& s = config_.sensors;
  auto code_of = [&](double g) {
    return current_code_from_A(current_A_ + s.current_sense_noise_A * g,
                               s.current_sense_full_scale_A, s.current_sense_bits);
  };
  if (!(s.current_sense_noise_A > 0.0)) return code_of(0.0);
  return code_of(gaussian_at(current_noise_key_, tick_));
}

std::int32_t Plant::encoder_count() const {
  const SensorConfig& s = config_.sensors;
  auto count_of = [&](double g) {
    const double counts = std::floor((s_m_ + s.encoder_noise_m * g) / s.encoder_resolution_m + 0.5);
    return static_cast<std::int32_t>(std::clamp(counts, -2147483648.0, 2147483647.0));
  };
  if (!(s.encoder_noise_m > 0.0)) return count_of(0.0);
  return count_of(gaussian_at(encoder_noise_key_, tick_));
}

double Plant::channel_pressure_Pa(int channel) const {
  if (channel < 1 || channel > static_cast<int>(kPressureChannels)) {
    throw std::out_of_range("pressure channel must be 1..6");
  }
  if (!phantom_ || phantom_->pressure_channel_count() == 0) return 0.0;
  return phantom_->channel_pressures_Pa(params_, normal_contact_force_N())[channel - 1];
}

std::uint16_t Plant::pressure_adc(int channel) const {
  return pressure_code(channel, channel_pressure_Pa(channel));
}

std::array<std::uint16_t, kPressureChannels> Plant::pressure_adcs() const {
  std::array<double, kPressureChannels> p{};
  if (phantom_ && phantom_->pressure_channel_count() != 0) {
    p = phantom_->channel_pressures_Pa(params_, normal_contact_force_N());
  }
  std::array<std::uint16_t, kPressureChannels> codes{};
  if (!(config_.sensors.pressure_noise_Pa > 0.0)) {
    for (std::size_t k = 0; k < kPressureChannels; ++k) codes[k] = pressure_code_at(p[k], 0.0);
    return codes;
  }
  for (std::size_t k = 0; k < kPressureChannels; ++k)
    codes[k] = pressure_code_at(p[k], gaussian_at(pressure_noise_keys_[k], tick_));
  return codes;
}

std::uint16_t Plant::pressure_code(int channel, double pressure_Pa) const {
  if (!(config_.sensors.pressure_noise_Pa > 0.0)) return pressure_code_at(pressure_Pa, 0.0);
  return pressure_code_at(pressure_Pa,
                          gaussian_at(pressure_noise_keys_[static_cast<std::size_t>(channel - 1)], tick_));
}

std::uint16_t Plant::pressure_code_at(double pressure_Pa, double g) const {
  const SensorConfig& s = config_.sensors;
  return pressure_code_from_Pa(pressure_Pa + s.pressure_noise_Pa * g, s.pressure_full_scale_Pa,
                               s.pressure_adc_bits);
}

}  // namespace palp::plant
