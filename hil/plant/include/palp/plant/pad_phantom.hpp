// SPDX-License-Identifier: Apache-2.0
// The paper's 2D pad (§V): 90 x 100 mm of Elastic 50A with a wavy top, a 9 x 9 probing grid and
// six sealed air channels read through Boyle's law (geometry: README.md "Pad").
//
//   x runs across the columns (100 mm), y across the rows (90 mm);
//   column c at x = inset_x + (c - 1) pitch, row r at y = inset_y + (r - 1) pitch;
//   top surface z_s = A sin(2 pi y / lambda) + tan(tilt) (x - size_x / 2) (waves along y; the
//   optional tilt about the y axis, default 0, turns the top about the pad's middle column
//   line: a positive tilt puts the top deeper, toward +z, at larger x; the base stays flat);
//   shallow channels 4, 5, 6 run along y under columns (2, 5, 8), their centre a fixed depth
//   below the local surface (they follow the waves); deep channels 1, 2, 3 run along x under
//   rows (8, 5, 2), straight, centre at a fixed z below the datum.
//
// Contact at (x, y): the sphere on a bonded layer of the local thickness, in series with a
// structural compliance c_0 + sum_k c_k w(d_k, z_k), where d_k is the lateral distance to
// channel k, z_k its centre depth below the surface and w(d, z) = (z^2 / (z^2 + d^2))^2 the
// Boussinesq attenuation of a point load's vertical stress integrated along a line. Channel k
// loses dV_k = A_k c_k w(d_k, z_k) F of volume (its share of the deflection times an effective
// area).
//
// Optional damping inclusion (pad_2d_damping): a vertical cylinder of the pad, a disc in (x, y),
// whose Kelvin-Voigt retardation time differs from the bulk's while its elastic law (and the
// standard linear solid's relaxation, if any) stays the bulk's: the same quasi-static stiffness,
// another damping. A site inside the disc (the apex's (x, y), edge included) takes its tau.
#pragma once

#include <array>

#include "palp/plant/phantom.hpp"

namespace palp::plant {

struct PadChannelClass {
  std::array<int, 3> lines{};       // shallow: columns; deep: rows (in channel order)
  double depth_m = 0.0;             // centre depth (shallow: below local surface; deep: below z=0)
  double length_m = 0.0;            // effective length for the enclosed volume (paper §V-D)
  double compliance_m_per_N = 0.0;  // c_k: structural compliance right above the channel
  double effective_area_m2 = 0.0;   // A_k: volume lost per metre of that deflection
};

struct PadDampingInclusion {
  double centre_x_m = 0.0, centre_y_m = 0.0;
  double radius_m = 0.0;              // 0: no inclusion
  double retardation_time_s = 0.0;    // Kelvin-Voigt tau inside the disc
};

struct PadPhantomSpec : MaterialSpec {
  double size_x_m = 0.0, size_y_m = 0.0, thickness_m = 0.0;
  int grid_count = 9;
  double grid_pitch_m = 0.0, grid_inset_x_m = 0.0, grid_inset_y_m = 0.0;
  double wave_amplitude_m = 0.0, wave_length_m = 0.0;
  double surface_tilt_about_y_rad = 0.0;  // file key surface_tilt_about_y_deg (optional, 0)
  double e_star_Pa = 0.0;
  double base_compliance_m_per_N = 0.0;
  double retardation_time_s = 0.0;
  double participating_mass_kg = 0.0;
  double ambient_pressure_Pa = 101325.0;
  double polytropic_exponent = 1.0;  // 1 = isothermal (paper §V-D), 1.4 = adiabatic
  double channel_diameter_m = 5e-3;
  double tube_bore_m = 1.5875e-3;
  double tube_length_m = 0.5;
  PadChannelClass deep;     // channels 1, 2, 3
  PadChannelClass shallow;  // channels 4, 5, 6
  PadDampingInclusion damping_inclusion;  // file keys damping_inclusion_* (optional, none)
};

class PadPhantom final : public Phantom {
 public:
  /// Throws PhantomError("name: ...") on inconsistent geometry.
  explicit PadPhantom(PadPhantomSpec spec);

  double surface_z_m(double x_m, double y_m) const override;
  ContactParams contact_params(double x_m, double y_m) const override;
  std::vector<ProbeSite> sites() const override;
  int pressure_channel_count() const override { return 6; }
  std::array<double, kPressureChannels> channel_pressures_Pa(const ContactParams& at_site,
                                                             double contact_force_N) const override;

  /// Enclosed volume of paper channel 1..6 (channel + tube), m^3.
  double channel_volume_m3(int channel) const;
  /// Centre depth of paper channel 1..6 below the surface at (x, y), m.
  double channel_depth_below_surface_m(int channel, double x_m, double y_m) const;
  /// Lateral distance from (x, y) to the axis of paper channel 1..6, m.
  double channel_distance_m(int channel, double x_m, double y_m) const;

  const PadPhantomSpec& spec() const { return spec_; }

 private:
  PadPhantomSpec spec_;
  std::array<double, kPressureChannels> volume_m3_{};
};

}  // namespace palp::plant
