// SPDX-License-Identifier: Apache-2.0
// Phantom files: the shipped ones load; malformed ones fail with one line "file:line: problem".
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "palp/plant/line_phantom.hpp"
#include "palp/plant/pad_phantom.hpp"
#include "palp/plant/phantom.hpp"

namespace palp::plant {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A valid two-position line phantom; line numbers below refer to it.
const std::string kGood =
    "# test phantom\n"                           // 1
    "format_version = 1\n"                       // 2
    "kind = line_1d\n"                           // 3
    "name = tiny\n"                              // 4
    "contact_law = hertz   # law\n"              // 5
    "viscoelasticity = kelvin_voigt\n"           // 6
    "mass_engage_depth_m = 1e-3\n"               // 7
    "position_count = 2\n"                       // 8
    "length_m = 0.03\n"                          // 9
    "width_m = 0.02\n"                           // 10
    "first_position_x_m = 0.01\n"                // 11
    "position_pitch_m = 0.01\n"                  // 12
    "surface_z_m = 0\n"                          // 13
    "e_star_Pa = 1e5, 2e5\n"                     // 14
    "layer_thickness_m = 0, 0.01\n"              // 15
    "structural_compliance_m_per_N = 0, 1e-3\n"  // 16
    "participating_mass_kg = 0, 0.01\n"          // 17
    "retardation_time_s = 2e-3, 2e-3\n";         // 18

std::string replace_line(const std::string& text, int line, const std::string& with) {
  std::string out;
  int n = 1;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const auto nl = text.find('\n', pos);
    const std::string l = text.substr(pos, nl - pos);
    if (n == line) {
      if (!with.empty()) out += with + "\n";
    } else {
      out += l + "\n";
    }
    ++n;
    pos = nl + 1;
  }
  return out;
}

std::string error_of(const std::string& text) {
  try {
    parse_phantom(text, "bad.phantom");
  } catch (const PhantomError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PhantomFile, ShippedPhantomsLoad) {
  for (const char* name : {"hollow_1d", "solid_1d", "insert_1d", "pad_2d"}) {
    const auto ph = load_shipped_phantom(name);
    EXPECT_EQ(ph->name(), name);
  }
  EXPECT_EQ(load_shipped_phantom("pad_2d")->kind(), PhantomKind::pad_2d);
  EXPECT_EQ(load_shipped_phantom("solid_1d")->sites().size(), 10u);
  EXPECT_EQ(load_shipped_phantom("pad_2d")->sites().size(), 81u);
}

TEST(PhantomFile, GoodTextParsesWithCommentsAndInterpolates) {
  const auto ph = parse_phantom(kGood, "good.phantom");
  const ContactParams mid = ph->contact_params(0.015, 0.0);
  EXPECT_DOUBLE_EQ(mid.e_star_Pa, 1.5e5);
  EXPECT_NEAR(mid.layer_thickness_m, 0.02, 1e-12);  // blended in 1/h: half of 1/0.01
  EXPECT_EQ(mid.law, ContactLaw::hertz);
}

TEST(PhantomFile, UnknownKeyIsReportedWithFileAndLine) {
  const std::string msg = error_of(replace_line(kGood, 14, "e_star_pa = 1e5, 2e5"));
  EXPECT_EQ(msg, "bad.phantom:14: unknown key 'e_star_pa' (kind = line_1d)");
}

TEST(PhantomFile, BadNumberIsReportedWithFileAndLine) {
  EXPECT_EQ(error_of(replace_line(kGood, 9, "length_m = 0.03x")),
            "bad.phantom:9: bad number '0.03x' for 'length_m'");
  EXPECT_EQ(error_of(replace_line(kGood, 15, "layer_thickness_m = 0, nan")),
            "bad.phantom:15: bad number 'nan' for 'layer_thickness_m'");
}

TEST(PhantomFile, MissingKeyIsReportedWithFileAndLine) {
  const std::string msg = error_of(replace_line(kGood, 18, ""));
  EXPECT_EQ(msg, "bad.phantom:17: missing required key 'retardation_time_s' (kind = line_1d)");
}

TEST(PhantomFile, OtherMistakesAreOneLineErrors) {
  const std::pair<int, std::string> cases[] = {
      {14, "e_star_Pa = 1e5"},          // too few values
      {14, "e_star_Pa = -1e5, 2e5"},    // out of range
      {5, "contact_law = hooke"},       // bad word
      {9, "length_m 0.03"},             // no '='
      {10, "length_m = 0.04"},          // duplicate key
      {2, "format_version = 2"},        // unknown format
      {12, "position_pitch_m = 0.05"},  // positions past the end
  };
  const char* expected[] = {
      "bad.phantom:14: 'e_star_Pa' needs 2 values, got 1",
      "bad.phantom:14: 'e_star_Pa' = -1e5 is out of range [1, 1e+10]",
      "bad.phantom:5: bad value 'hooke' for 'contact_law' (expected hertz | sneddon)",
      "bad.phantom:9: expected 'key = value'",
      "bad.phantom:10: duplicate key 'length_m' (first at line 9)",
      "bad.phantom:2: 'format_version' = 2 is out of range [1, 1]",
      "bad.phantom:12: positions run past length_m",
  };
  for (std::size_t k = 0; k < std::size(cases); ++k) {
    const std::string msg = error_of(replace_line(kGood, cases[k].first, cases[k].second));
    EXPECT_EQ(msg, expected[k]);
    EXPECT_THAT(msg, Not(HasSubstr("\n")));
  }
}

TEST(PhantomFile, SlsKeysAreRequiredOnlyForTheStandardLinearSolid) {
  const std::string sls = replace_line(kGood, 6, "viscoelasticity = standard_linear_solid");
  EXPECT_EQ(error_of(sls),
            "bad.phantom:18: missing required key 'sls_relaxation_time_s' "
            "(viscoelasticity = standard_linear_solid)");
  const auto ph = parse_phantom(sls + "sls_relaxation_time_s = 1.5\nsls_strength = 0.4\n", "x");
  EXPECT_EQ(ph->contact_params(0.01, 0).viscoelasticity, Viscoelasticity::standard_linear_solid);
  EXPECT_DOUBLE_EQ(ph->contact_params(0.01, 0).sls_strength, 0.4);
}

TEST(PhantomFile, UnreadableFileNamesTheFile) {
  try {
    load_phantom("/nonexistent/nowhere.phantom");
    FAIL() << "no error";
  } catch (const PhantomError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("nowhere.phantom:0: cannot open"));
  }
}

}  // namespace
}  // namespace palp::plant
