// SPDX-License-Identifier: Apache-2.0
// PadPhantom: the 2D pad with a wavy top, channels under columns and rows, Boyle pressures.
#include "palp/plant/pad_phantom.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace palp::plant {
namespace {

// Boussinesq: a point load's vertical stress integrated along a line at depth z and lateral
// offset d is 2 F z^3 / (pi (z^2 + d^2)^2); normalised to 1 right above the line.
double attenuation(double d, double z) {
  const double z2 = z * z;
  const double r = z2 / (z2 + d * d);
  return r * r;
}

double disc_area(double diameter) { return 0.25 * std::numbers::pi * diameter * diameter; }

// The wavy, possibly tilted top (without the footprint check).
double top_z(const PadPhantomSpec& s, double x_m, double y_m) {
  return s.wave_amplitude_m * std::sin(2.0 * std::numbers::pi * y_m / s.wave_length_m) +
         std::tan(s.surface_tilt_about_y_rad) * (x_m - 0.5 * s.size_x_m);
}

// How far the top rises above or sinks below z = 0 anywhere on the pad.
double top_excursion(const PadPhantomSpec& s) {
  return s.wave_amplitude_m + std::abs(std::tan(s.surface_tilt_about_y_rad)) * 0.5 * s.size_x_m;
}

}  // namespace

PadPhantom::PadPhantom(PadPhantomSpec spec)
    : Phantom(spec, PhantomKind::pad_2d), spec_(std::move(spec)) {
  const PadPhantomSpec& s = spec_;
  const double span = static_cast<double>(s.grid_count - 1) * s.grid_pitch_m;
  if (s.grid_inset_x_m + span > s.size_x_m || s.grid_inset_y_m + span > s.size_y_m) {
    throw PhantomError(name() + ": the grid runs past the pad");
  }
  if (!(std::abs(s.surface_tilt_about_y_rad) < std::numbers::pi / 4.0)) {
    throw PhantomError(name() + ": the surface tilt must be below 45 degrees");
  }
  const PadDampingInclusion& inc = s.damping_inclusion;
  if (inc.radius_m > 0.0 &&
      (inc.centre_x_m - inc.radius_m < 0.0 || inc.centre_x_m + inc.radius_m > s.size_x_m ||
       inc.centre_y_m - inc.radius_m < 0.0 || inc.centre_y_m + inc.radius_m > s.size_y_m)) {
    throw PhantomError(name() + ": the damping inclusion runs past the pad");
  }
  const double r = 0.5 * s.channel_diameter_m;
  const double top = top_excursion(s);
  if (s.shallow.depth_m <= r || s.deep.depth_m - top <= r ||
      s.deep.depth_m + r >= s.thickness_m - s.wave_amplitude_m || top >= s.thickness_m) {
    throw PhantomError(name() + ": a channel breaks through the top or the base");
  }
  for (int ch = 1; ch <= 6; ++ch) {
    const PadChannelClass& cls = ch <= 3 ? s.deep : s.shallow;
    volume_m3_[ch - 1] =
        disc_area(s.channel_diameter_m) * cls.length_m + disc_area(s.tube_bore_m) * s.tube_length_m;
  }
}

double PadPhantom::surface_z_m(double x_m, double y_m) const {
  if (x_m < 0.0 || x_m > spec_.size_x_m || y_m < 0.0 || y_m > spec_.size_y_m) {
    return std::numeric_limits<double>::infinity();
  }
  return top_z(spec_, x_m, y_m);
}

double PadPhantom::channel_distance_m(int channel, double x_m, double y_m) const {
  const PadPhantomSpec& s = spec_;
  if (channel >= 1 && channel <= 3) {
    const int row = s.deep.lines[static_cast<std::size_t>(channel - 1)];
    return std::abs(y_m - (s.grid_inset_y_m + (row - 1) * s.grid_pitch_m));
  }
  if (channel >= 4 && channel <= 6) {
    const int col = s.shallow.lines[static_cast<std::size_t>(channel - 4)];
    return std::abs(x_m - (s.grid_inset_x_m + (col - 1) * s.grid_pitch_m));
  }
  throw std::out_of_range("pad channel must be 1..6");
}

double PadPhantom::channel_depth_below_surface_m(int channel, double x_m, double y_m) const {
  if (channel >= 1 && channel <= 3) {
    return spec_.deep.depth_m - top_z(spec_, x_m, y_m);  // straight along x, at a fixed z
  }
  if (channel >= 4 && channel <= 6) return spec_.shallow.depth_m;
  throw std::out_of_range("pad channel must be 1..6");
}

double PadPhantom::channel_volume_m3(int channel) const {
  if (channel < 1 || channel > 6) throw std::out_of_range("pad channel must be 1..6");
  return volume_m3_[static_cast<std::size_t>(channel - 1)];
}

ContactParams PadPhantom::contact_params(double x_m, double y_m) const {
  const PadPhantomSpec& s = spec_;
  ContactParams p;
  p.law = s.law;
  p.viscoelasticity = s.viscoelasticity;
  p.sls_relaxation_time_s = s.sls_relaxation_time_s;
  p.sls_strength = s.sls_strength;
  p.mass_engage_depth_m = s.mass_engage_depth_m;
  p.e_star_Pa = s.e_star_Pa;
  const PadDampingInclusion& inc = s.damping_inclusion;
  p.retardation_time_s = inc.radius_m > 0.0 && std::hypot(x_m - inc.centre_x_m,
                                                          y_m - inc.centre_y_m) <= inc.radius_m
                             ? inc.retardation_time_s
                             : s.retardation_time_s;
  p.participating_mass_kg = s.participating_mass_kg;
  p.layer_thickness_m = s.thickness_m - top_z(s, x_m, y_m);
  double compliance = s.base_compliance_m_per_N;
  for (int ch = 1; ch <= 6; ++ch) {
    const PadChannelClass& cls = ch <= 3 ? s.deep : s.shallow;
    const double w =
        attenuation(channel_distance_m(ch, x_m, y_m), channel_depth_below_surface_m(ch, x_m, y_m));
    compliance += cls.compliance_m_per_N * w;
    p.channel_gain_m3_per_N[static_cast<std::size_t>(ch - 1)] =
        cls.effective_area_m2 * cls.compliance_m_per_N * w;
  }
  p.structural_compliance_m_per_N = compliance;
  return p;
}

std::array<double, kPressureChannels> PadPhantom::channel_pressures_Pa(
    const ContactParams& at_site, double contact_force_N) const {
  std::array<double, kPressureChannels> out{};
  const double p0 = spec_.ambient_pressure_Pa;
  const double n = spec_.polytropic_exponent;
  for (std::size_t k = 0; k < kPressureChannels; ++k) {
    const double v1 = volume_m3_[k];
    const double dv = std::min(at_site.channel_gain_m3_per_N[k] * contact_force_N, 0.99 * v1);
    const double ratio = v1 / (v1 - dv);
    out[k] = p0 * ((n == 1.0 ? ratio : std::pow(ratio, n)) - 1.0);
  }
  return out;
}

std::vector<ProbeSite> PadPhantom::sites() const {
  std::vector<ProbeSite> out;
  const PadPhantomSpec& s = spec_;
  for (int r = 1; r <= s.grid_count; ++r) {
    for (int c = 1; c <= s.grid_count; ++c) {
      out.push_back({r, c, s.grid_inset_x_m + (c - 1) * s.grid_pitch_m,
                     s.grid_inset_y_m + (r - 1) * s.grid_pitch_m});
    }
  }
  return out;
}

}  // namespace palp::plant
