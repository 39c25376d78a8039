// SPDX-License-Identifier: Apache-2.0
// Phantoms: specimens the probe presses on, each loaded from a readable parameter file in
// hil/plant/phantoms/ (format and every key: README.md "Phantom files").
//
// Phantom frame: x, y horizontal, +z into the specimen (down), z = 0 at the phantom's datum (the
// flat top of a 1D object, the mean top of the pad); the probe's axis is +z by default and may
// tilt (Plant::set_probe_axis). The surface height z_s(x, y) is the z of the top surface; a
// vertical tip apex at z_tip indents a flat top by delta = z_tip - z_s. Outside the footprint
// z_s is +infinity (nothing to touch).
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "palp/plant/contact.hpp"

namespace palp::plant {

/// A malformed phantom file: the message is one line, "file:line: problem".
class PhantomError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class PhantomKind { line_1d, pad_2d };

/// What every phantom file states about its material (keys common to all kinds).
struct MaterialSpec {
  std::string name;
  ContactLaw law = ContactLaw::sneddon;
  Viscoelasticity viscoelasticity = Viscoelasticity::kelvin_voigt;
  double sls_relaxation_time_s = 0.0;
  double sls_strength = 0.0;
  double mass_engage_depth_m = 1e-3;
  /// Coulomb friction of the tip on the material (optional key friction_coefficient; README.md
  /// "Oblique contact" has the default's source).
  double friction_coefficient = ContactParams{}.friction_coefficient;
};

/// A named probing site in the phantom frame (1D: position k; pad: row r, column c).
struct ProbeSite {
  int row = 0;     // pad row 1..9; 0 for a 1D object
  int column = 0;  // pad column 1..9; 1D position 1..10
  double x_m = 0.0;
  double y_m = 0.0;
};

class Phantom {
 public:
  virtual ~Phantom() = default;

  const std::string& name() const { return name_; }
  PhantomKind kind() const { return kind_; }

  /// z of the top surface at (x, y), m; +infinity outside the footprint.
  virtual double surface_z_m(double x_m, double y_m) const = 0;

  /// The contact law at (x, y) (interpolated between the file's sites).
  virtual ContactParams contact_params(double x_m, double y_m) const = 0;

  /// All probing sites the paper names (1D: positions 1..10; pad: the 9 x 9 grid).
  virtual std::vector<ProbeSite> sites() const = 0;

  /// 1D position k (1..10); throws std::out_of_range if there is none.
  ProbeSite position(int k) const;
  /// Pad grid point (row, column), 1-based; throws std::out_of_range if there is none.
  ProbeSite grid_point(int row, int column) const;

  /// Coulomb friction coefficient of the tip on the material (MaterialSpec).
  double friction_coefficient() const { return friction_coefficient_; }

  /// Number of sealed pressure channels (0 or 6).
  virtual int pressure_channel_count() const { return 0; }

  /// Gauge pressure of each channel (index 0 = paper channel 1), Pa, given the contact law at
  /// the site touched and the contact force: Boyle (polytropic) compression of channel + tube by
  /// dV = gain * F. All zero for phantoms without channels.
  virtual std::array<double, kPressureChannels> channel_pressures_Pa(const ContactParams& at_site,
                                                                     double contact_force_N) const;

 protected:
  Phantom(const MaterialSpec& material, PhantomKind kind)
      : name_(material.name), kind_(kind), friction_coefficient_(material.friction_coefficient) {}

 private:
  std::string name_;
  PhantomKind kind_;
  double friction_coefficient_;
};

/// Parse phantom text; source_name names it in error messages. Throws PhantomError.
std::shared_ptr<const Phantom> parse_phantom(std::string_view text, std::string_view source_name);

/// Load a phantom file. Throws PhantomError (also when the file cannot be read).
std::shared_ptr<const Phantom> load_phantom(const std::filesystem::path& file);

/// The shipped phantoms (hil/plant/phantoms/*.phantom, built into the library as text, so an
/// installed library needs no path to them): "hollow_1d", "insert_1d", "pad_2d", "pad_2d_steep",
/// "plane_tilted_10", "solid_1d", "wedge_0", "wedge_25".
std::vector<std::string_view> shipped_phantom_names();
/// A shipped phantom's text; PhantomError naming the shipped ones for another name.
std::string_view shipped_phantom_text(std::string_view name);
/// Load a shipped phantom by name (error messages name it "<name>.phantom"). PhantomError for a
/// name that is not shipped.
std::shared_ptr<const Phantom> load_shipped_phantom(std::string_view name);

/// Where a spherical tip lowered along +z first touches a phantom (README.md "Sphere tip").
struct SphereTouch {
  bool touches = false;    ///< false: nothing under the tip's disc (all values +infinity / 0)
  double apex_z_m = 0.0;   ///< the tip apex's z at first touch: the contact gap's zero
  double point_x_m = 0.0;  ///< the touched point on the surface (phantom frame)
  double point_y_m = 0.0;
  double point_z_m = 0.0;
  /// Unit surface normal at the touched point, pointing into the specimen (z component > 0):
  /// from the sphere's centre to the touched point. (0, 0, 1) on a flat top.
  std::array<double, 3> normal{0.0, 0.0, 1.0};
};

/// First touch of a sphere of radius_m whose apex is at (x_m, y_m): the apex height
///   z_touch = min over u^2 + v^2 <= R^2 of [ z_s(x + u, y + v) + R - sqrt(R^2 - u^2 - v^2) ],
/// found by a coarse polar scan of the disc, a pattern search down to R/256 and Newton steps on
/// finite differences (the pattern search goes on to 1 nm where they do not improve): z_touch
/// to far below 0.1 um and the normal to ~1e-6 rad on smooth surfaces, ~4 us a call. Where the
/// best point is the apex itself (a flat top) z_touch equals z_s(x, y) exactly.
/// Throws std::invalid_argument if radius_m <= 0.
SphereTouch sphere_touch(const Phantom& phantom, double x_m, double y_m, double radius_m);

/// The same for a probe whose axis is the unit vector `axis` (phantom frame, axis z > 0): the
/// sphere moves along the line through (x_m, y_m, 0) in that direction. The disc is searched
/// across the axis and each of its points' lines is met with the surface by Newton; apex_z_m is
/// the apex's z at first touch (its depth along the axis is (z_tip - apex_z_m) / axis_z), the
/// normal points into the specimen. axis = (0, 0, 1) is sphere_touch(phantom, x_m, y_m, R)
/// exactly. Throws std::invalid_argument for a radius <= 0 or an axis that is not a unit vector
/// with z > 0.
SphereTouch sphere_touch_along(const Phantom& phantom, double x_m, double y_m,
                               const std::array<double, 3>& axis, double radius_m);

/// Where the axis line through (x_m, y_m, 0) along `axis` crosses the surface: its parameter t
/// (the point (x, y, 0) + t axis), +infinity where there is none; surface_z_m for a vertical axis.
double surface_along_axis_m(const Phantom& phantom, double x_m, double y_m,
                            const std::array<double, 3>& axis);

}  // namespace palp::plant
