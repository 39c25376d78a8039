// SPDX-License-Identifier: Apache-2.0
// Key lists and value ranges of the line_1d and pad_2d phantom files.
#include "phantom_read.hpp"

#include <exception>
#include <numbers>

#include "palp/plant/line_phantom.hpp"
#include "palp/plant/pad_phantom.hpp"

namespace palp::plant::detail {
namespace {

const std::vector<std::string_view> kCommonKeys = {
    "format_version", "kind", "name", "contact_law", "viscoelasticity", "mass_engage_depth_m"};
const std::vector<std::string_view> kSlsKeys = {"sls_relaxation_time_s", "sls_strength"};
const std::vector<std::string_view> kOptionalCommonKeys = {"friction_coefficient"};

std::vector<std::string_view> join(std::vector<std::string_view> a,
                                   const std::vector<std::string_view>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Fills the keys every phantom kind has into c.
void read_common(const KeyValueFile& f, std::string_view context, MaterialSpec& c) {
  f.require(kCommonKeys, context);
  c.name = f.word("name", {});
  c.law = f.word("contact_law", {"hertz", "sneddon"}) == "hertz" ? ContactLaw::hertz
                                                                 : ContactLaw::sneddon;
  const std::string ve = f.word("viscoelasticity", {"kelvin_voigt", "standard_linear_solid"});
  if (ve == "standard_linear_solid") {
    c.viscoelasticity = Viscoelasticity::standard_linear_solid;
    f.require(kSlsKeys, "viscoelasticity = standard_linear_solid");
  }
  if (f.has("sls_relaxation_time_s")) c.sls_relaxation_time_s = f.number("sls_relaxation_time_s", 1e-6, 1e6);
  if (f.has("sls_strength")) c.sls_strength = f.number("sls_strength", 0.0, 100.0);
  c.mass_engage_depth_m = f.number("mass_engage_depth_m", 0.0, 0.1);
  if (f.has("friction_coefficient")) {
    c.friction_coefficient = f.number("friction_coefficient", 0.0, 10.0);
  }
}

// Construct, reporting the class's consistency errors at the file's "kind" line.
template <class T, class Spec>
std::shared_ptr<const Phantom> build(const KeyValueFile& f, Spec spec) {
  try {
    return std::make_shared<T>(std::move(spec));
  } catch (const PhantomError& e) {
    f.fail(f.line_of("kind"), e.what());
  }
}

}  // namespace

std::shared_ptr<const Phantom> read_line_phantom(const KeyValueFile& f) {
  // clang-format off
  const std::vector<std::string_view> own = {
      "position_count", "length_m", "width_m", "first_position_x_m", "position_pitch_m",
      "surface_z_m", "e_star_Pa", "layer_thickness_m", "structural_compliance_m_per_N",
      "participating_mass_kg", "retardation_time_s"};
  // clang-format on
  const char* context = "kind = line_1d";
  f.reject_unknown(join(join(join(kCommonKeys, kSlsKeys), kOptionalCommonKeys), own), context);
  f.require(own, context);
  LinePhantomSpec s;
  read_common(f, context, s);
  const auto n = static_cast<std::size_t>(f.integer("position_count", 1, 100));
  s.length_m = f.number("length_m", 1e-3, 10.0);
  s.width_m = f.number("width_m", 1e-3, 10.0);
  s.first_position_x_m = f.number("first_position_x_m", 0.0, s.length_m);
  s.position_pitch_m = f.number("position_pitch_m", 1e-4, 10.0);
  if (s.first_position_x_m + static_cast<double>(n - 1) * s.position_pitch_m > s.length_m) {
    f.fail(f.line_of("position_pitch_m"), "positions run past length_m");
  }
  s.surface_z_m = f.number("surface_z_m", -1.0, 1.0);
  s.e_star_Pa = f.numbers("e_star_Pa", n, 1.0, 1e10);
  s.layer_thickness_m = f.numbers("layer_thickness_m", n, 0.0, 1.0);
  s.structural_compliance_m_per_N = f.numbers("structural_compliance_m_per_N", n, 0.0, 1.0);
  s.participating_mass_kg = f.numbers("participating_mass_kg", n, 0.0, 10.0);
  s.retardation_time_s = f.numbers("retardation_time_s", n, 0.0, 10.0);
  return build<LinePhantom>(f, std::move(s));
}

std::shared_ptr<const Phantom> read_pad_phantom(const KeyValueFile& f) {
  // clang-format off
  const std::vector<std::string_view> own = {
      "size_x_m", "size_y_m", "thickness_m", "grid_count", "grid_pitch_m", "grid_inset_x_m",
      "grid_inset_y_m", "wave_amplitude_m", "wave_length_m", "e_star_Pa",
      "base_compliance_m_per_N", "retardation_time_s", "participating_mass_kg",
      "ambient_pressure_Pa", "polytropic_exponent", "channel_diameter_m", "tube_bore_m",
      "tube_length_m", "deep_channel_rows", "deep_channel_depth_m", "deep_channel_length_m",
      "deep_channel_compliance_m_per_N", "deep_channel_effective_area_m2",
      "shallow_channel_columns", "shallow_channel_depth_m", "shallow_channel_length_m",
      "shallow_channel_compliance_m_per_N", "shallow_channel_effective_area_m2"};
  const std::vector<std::string_view> inclusion = {
      "damping_inclusion_centre_x_m", "damping_inclusion_centre_y_m",
      "damping_inclusion_radius_m", "damping_inclusion_retardation_time_s"};
  const std::vector<std::string_view> optional = join({"surface_tilt_about_y_deg"}, inclusion);
  // clang-format on
  const char* context = "kind = pad_2d";
  const auto common = join(join(kCommonKeys, kSlsKeys), kOptionalCommonKeys);
  f.reject_unknown(join(join(common, own), optional), context);
  f.require(own, context);
  PadPhantomSpec s;
  read_common(f, context, s);
  s.size_x_m = f.number("size_x_m", 1e-3, 10.0);
  s.size_y_m = f.number("size_y_m", 1e-3, 10.0);
  s.thickness_m = f.number("thickness_m", 1e-3, 1.0);
  s.grid_count = f.integer("grid_count", 1, 99);
  s.grid_pitch_m = f.number("grid_pitch_m", 1e-4, 1.0);
  s.grid_inset_x_m = f.number("grid_inset_x_m", 0.0, s.size_x_m);
  s.grid_inset_y_m = f.number("grid_inset_y_m", 0.0, s.size_y_m);
  s.wave_amplitude_m = f.number("wave_amplitude_m", 0.0, 0.1);
  s.wave_length_m = f.number("wave_length_m", 1e-3, 10.0);
  if (f.has("surface_tilt_about_y_deg")) {
    s.surface_tilt_about_y_rad =
        f.number("surface_tilt_about_y_deg", -44.0, 44.0) * std::numbers::pi / 180.0;
  }
  s.e_star_Pa = f.number("e_star_Pa", 1.0, 1e10);
  s.base_compliance_m_per_N = f.number("base_compliance_m_per_N", 0.0, 1.0);
  s.retardation_time_s = f.number("retardation_time_s", 0.0, 10.0);
  s.participating_mass_kg = f.number("participating_mass_kg", 0.0, 10.0);
  s.ambient_pressure_Pa = f.number("ambient_pressure_Pa", 1e3, 1e7);
  s.polytropic_exponent = f.number("polytropic_exponent", 1.0, 1.67);
  s.channel_diameter_m = f.number("channel_diameter_m", 1e-4, 0.1);
  s.tube_bore_m = f.number("tube_bore_m", 0.0, 0.1);
  s.tube_length_m = f.number("tube_length_m", 0.0, 100.0);
  const int n = s.grid_count;
  s.deep.lines = [&] {
    const auto v = f.integers("deep_channel_rows", 3, 1, n);
    return std::array<int, 3>{v[0], v[1], v[2]};
  }();
  s.deep.depth_m = f.number("deep_channel_depth_m", 0.0, 1.0);
  s.deep.length_m = f.number("deep_channel_length_m", 1e-3, 10.0);
  s.deep.compliance_m_per_N = f.number("deep_channel_compliance_m_per_N", 0.0, 1.0);
  s.deep.effective_area_m2 = f.number("deep_channel_effective_area_m2", 0.0, 1.0);
  s.shallow.lines = [&] {
    const auto v = f.integers("shallow_channel_columns", 3, 1, n);
    return std::array<int, 3>{v[0], v[1], v[2]};
  }();
  s.shallow.depth_m = f.number("shallow_channel_depth_m", 0.0, 1.0);
  s.shallow.length_m = f.number("shallow_channel_length_m", 1e-3, 10.0);
  s.shallow.compliance_m_per_N = f.number("shallow_channel_compliance_m_per_N", 0.0, 1.0);
  s.shallow.effective_area_m2 = f.number("shallow_channel_effective_area_m2", 0.0, 1.0);
  if (f.has("damping_inclusion_radius_m") || f.has("damping_inclusion_centre_x_m") ||
      f.has("damping_inclusion_centre_y_m") || f.has("damping_inclusion_retardation_time_s")) {
    f.require(inclusion, "a damping inclusion");  // all four keys or none
    PadDampingInclusion& inc = s.damping_inclusion;
    inc.centre_x_m = f.number("damping_inclusion_centre_x_m", 0.0, s.size_x_m);
    inc.centre_y_m = f.number("damping_inclusion_centre_y_m", 0.0, s.size_y_m);
    inc.radius_m = f.number("damping_inclusion_radius_m", 1e-4, 1.0);
    inc.retardation_time_s = f.number("damping_inclusion_retardation_time_s", 0.0, 10.0);
  }
  return build<PadPhantom>(f, std::move(s));
}

}  // namespace palp::plant::detail
