// SPDX-License-Identifier: Apache-2.0
// Depth sensitivity on the pad (issue 24, docs/depth-sensitivity.md): how much softer than their
// neighbours the rows over the deep channels (2, 5, 8: channels 3, 2, 1) and the columns over
// the shallow ones (2, 5, 8: channels 4, 5, 6) are, as a function of the object force reached.
// The stiffness at a force F is the tangent dF_o/d(delta) where the force is F; a line's contrast
// is 1 - k(line) / mean(k of its two neighbouring lines), at the same point of the other axis.
// Two sources, each printed as the table the doc quotes:
//   - the pad's contact law (palp-sim's plant, static): any force, beyond the coil's limits too;
//     flat (along the surface normal: the channels alone) and sloped (along the vertical probe
//     on the pad's wavy top, as palp-sim evaluates it: the slope adds to or takes from a row);
//   - palp-sim linked in (virtual time): indent() at 15 points with the ramp to the coil's
//     current clamp (3.2 A), the slope of F_o against z over the loading plateaus within 0.5 N
//     of F (F_o = K_f (i - I_c) - k_v (z - z_float), the paper's constants).
// Regenerate the figures: ctest --test-dir build/release-with-assertions -R DepthSensitivity -V
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <vector>

#include "palp/indent.hpp"
#include "palp/map.hpp"
#include "palp/plant/contact.hpp"
#include "palp/plant/phantom.hpp"
#include "palp/probe.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"
#include "sanitized.hpp"
#include "trace_sim.hpp"

// named, not anonymous: the unity build joins this file with the other sdk_sim_tests sources
namespace depth_sensitivity_test {

using palp::plant::ContactParams;
using palp::plant::ProbeSite;
using palp::sim::test::kSanitized;

constexpr double kTipRadius_m = 2.5e-3;
const std::vector<double> kLawForces_N{0.5, 1.0, 1.459, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0,
                                       7.66, 10.0, 15.0, 20.0, 30.0, 50.0};

const palp::plant::Phantom& pad() {
  static const auto ph = palp::plant::load_shipped_phantom("pad_2d");
  return *ph;
}

// The law's tangent stiffness at (row, column) where its force is F (bisection on the depth).
// Flat: the law along the surface normal, the channels alone. Sloped: along a vertical probe on
// the pad's wavy top (up to 11.8 degrees), the oblique law palp-sim's plant evaluates (normal
// approach delta cos(theta) plus Mindlin's tangential part: hil/plant/README.md).
enum class Law { flat, sloped };
double law_k_at_force(int row, int column, double force_N, Law law = Law::flat,
                      double* depth_m = nullptr) {
  const ProbeSite s = pad().grid_point(row, column);
  ContactParams p = pad().contact_params(s.x_m, s.y_m);
  p.friction_coefficient = pad().friction_coefficient();
  const double cos_theta =
      law == Law::flat ? 1.0
                       : palp::plant::sphere_touch(pad(), s.x_m, s.y_m, kTipRadius_m).normal[2];
  auto at = [&](double d) {
    return palp::plant::oblique_elastic_contact(p, kTipRadius_m, d, cos_theta);
  };
  double lo = 0, hi = 0.02;
  for (int k = 0; k < 80; ++k) {
    const double mid = 0.5 * (lo + hi);
    (at(mid).force_N < force_N ? lo : hi) = mid;
  }
  if (depth_m) *depth_m = lo;
  return at(lo).stiffness_N_per_m;
}

// 1 - k(line) / mean(neighbours), for a row (deep) or a column (shallow) through (row, column)
template <class K>
double row_contrast(const K& k, int row, int column) {
  return 1.0 - k(row, column) / (0.5 * (k(row - 1, column) + k(row + 1, column)));
}
template <class K>
double column_contrast(const K& k, int row, int column) {
  return 1.0 - k(row, column) / (0.5 * (k(row, column - 1) + k(row, column + 1)));
}

// rows 2, 5, 8 against their neighbours, each the mean over the six columns off the shallow
// channels; and the mean of the three
std::array<double, 4> deep_row_contrasts(double force_N, Law law) {
  auto k = [force_N, law](int r, int c) { return law_k_at_force(r, c, force_N, law); };
  std::array<double, 4> out{};
  for (int i = 0; i < 3; ++i) {
    for (int c : {1, 3, 4, 6, 7, 9}) out[i] += row_contrast(k, 2 + 3 * i, c) / 6;
    out[3] += out[i] / 3;
  }
  return out;
}

TEST(DepthSensitivity, LawDeepRowContrastGrowsWithForceButStaysBelowTenPercentUpTo50N) {
  std::printf("pad contact law: contrast against the neighbouring lines, tangent stiffness at F\n");
  std::printf("  F_N  depth_mm  flat: row2  row5  row8  mean | sloped: row2  row5  row8 | "
              "shallow cols\n");
  double previous_deep = 0;
  for (double f : kLawForces_N) {
    const auto flat = deep_row_contrasts(f, Law::flat);
    const auto sloped = deep_row_contrasts(f, Law::sloped);
    auto k = [f](int r, int c) { return law_k_at_force(r, c, f); };
    double shallow = 0;
    for (int r = 1; r <= 9; ++r)
      for (int c : {2, 5, 8}) shallow += column_contrast(k, r, c) / 27;
    double depth = 0;
    law_k_at_force(4, 4, f, Law::flat, &depth);
    std::printf("%6.2f  %6.2f   %5.1f%% %5.1f%% %5.1f%% %5.1f%% |  %5.1f%% %5.1f%% %5.1f%% | %5.1f%%\n",
                f, depth * 1e3, 100 * flat[0], 100 * flat[1], 100 * flat[2], 100 * flat[3],
                100 * sloped[0], 100 * sloped[1], 100 * sloped[2], 100 * shallow);
    EXPECT_GT(flat[3], previous_deep) << f << " N";  // more force, more of the deep channel
    EXPECT_LT(flat[3], 0.10) << f << " N";
    for (double c : sloped) EXPECT_LT(c, 0.10) << f << " N";
    EXPECT_GT(shallow, 0.30) << f << " N";
    previous_deep = flat[3];
  }
}

// The law's contrast at infinite force: the series compliances alone (c_0 + sum c_k w), which
// the tangent approaches as the sphere's own stiffness grows without bound.
TEST(DepthSensitivity, LawDeepRowContrastIsBoundedByTheSeriesCompliances) {
  auto k_inf = [](int r, int c) {
    const ProbeSite s = pad().grid_point(r, c);
    return 1.0 / pad().contact_params(s.x_m, s.y_m).structural_compliance_m_per_N;
  };
  double bound = 0;
  for (int r : {2, 5, 8})
    for (int c : {1, 3, 4, 6, 7, 9}) bound = std::max(bound, row_contrast(k_inf, r, c));
  std::printf("deep rows: at most %.1f %% softer at any force (series compliances alone)\n",
              100 * bound);
  EXPECT_LT(bound, 0.10);
  for (int r : {2, 5, 8})
    for (int c : {1, 3, 4, 6, 7, 9})
      EXPECT_LT(row_contrast([](int rr, int cc) { return law_k_at_force(rr, cc, 50.0); }, r, c),
                row_contrast(k_inf, r, c));
}

// One indentation at a grid point of the pad in palp-sim: the loading plateaus' (z, F_o).
struct Plateau {
  double z_m, force_N;
};
std::vector<Plateau> indent_plateaus(palp::sim::InprocSimulator& sim, palp::Probe& probe, int row,
                                     int column, const palp::IndentationSettings& s) {
  const ProbeSite site = pad().grid_point(row, column);
  const auto touch = palp::plant::sphere_touch(pad(), site.x_m, site.y_m, kTipRadius_m);
  char line[96];
  std::snprintf(line, sizeof line, "mount %.6f %.6f %.6f", site.x_m * 1e3, site.y_m * 1e3,
                (touch.apex_z_m - 0.025) * 1e3);  // the floating tip (25 mm of stroke) touches
  EXPECT_EQ(sim.control(line).rfind("ok", 0), 0u) << line;
  const palp::IndentationRun run = palp::indent(probe, s);
  EXPECT_EQ(run.program.end, palp::proto::ProgramEnd::completed);
  const palp::analysis::Curve c = palp::curve_of(run.recording);
  const auto& a = s.analysis;
  std::map<long, std::pair<int, Plateau>> sums;  // by commanded level, first repetition, loading
  double top = 0;
  for (Eigen::Index k = 0; k < c.z_m.size(); ++k) {
    if ((c.rep.size() && c.rep[k] != c.rep[0]) || c.i_cmd_A[k] < top - 1e-6) break;
    top = std::max(top, c.i_cmd_A[k]);
    auto& [n, p] = sums[std::lround(c.i_cmd_A[k] / s.step_A)];
    ++n;
    p.z_m += c.z_m[k];
    p.force_N += a.force_constant_N_per_A * (c.i_A[k] - a.contact_current_A) -
                 a.spring_N_per_m * (c.z_m[k] - run.float_z_m);
  }
  std::vector<Plateau> out;
  for (const auto& [level, np] : sums)
    out.push_back({np.second.z_m / np.first, np.second.force_N / np.first});
  return out;
}

// least-squares slope of F_o against z over the plateaus within half_band_N of force_N
double slope_at_force(const std::vector<Plateau>& ps, double force_N, double half_band_N = 0.5) {
  double n = 0, sz = 0, sf = 0, szz = 0, szf = 0;
  for (const Plateau& p : ps)
    if (std::abs(p.force_N - force_N) <= half_band_N) {
      ++n, sz += p.z_m, sf += p.force_N, szz += p.z_m * p.z_m, szf += p.z_m * p.force_N;
    }
  if (n < 5) return std::nan("");
  return (n * szf - sz * sf) / (n * szz - sz * sz);
}

TEST(DepthSensitivity, PalpSimRampsToTheClampShowTheLawsContrastAtEveryForce) {
  if (kSanitized) GTEST_SKIP() << "15 ramps of ~17 s device time: the release build runs it";
  palp::sim::InprocSimulator sim({.phantom = "pad_2d"});
  palp::Probe probe(sim.transport());
  palp::IndentationSettings s = palp::IndentationSettings::preset(palp::IndentationPreset::two_d);
  s.repetitions = 1;
  s.stop_A = 3.2;  // the firmware's default current clamp (current_clamp_A)
  s.zero_pressure = false;
  // rows 1-9 at column 4 (off the shallow channels): the deep rows 2, 5, 8; rows 4-6 at columns
  // 5 and 6: the shallow column 5 between 4 and 6
  std::map<std::pair<int, int>, std::vector<Plateau>> at;
  for (int r = 1; r <= 9; ++r) at[{r, 4}] = indent_plateaus(sim, probe, r, 4, s);
  for (int r = 4; r <= 6; ++r)
    for (int c : {5, 6}) at[{r, c}] = indent_plateaus(sim, probe, r, c, s);
  double top_force = 1e9;
  for (const auto& [rc, ps] : at) top_force = std::min(top_force, ps.back().force_N);
  std::printf("palp-sim, ramps 0.5 -> 3.2 A (lowest top F_o %.2f N): contrast against neighbours\n",
              top_force);
  std::printf("  F_N   row2 c4  row5 c4  row8 c4  col5 r4-6 | sloped law: row2/5/8 c4, col5\n");
  for (double f : {1.0, 1.459, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0}) {
    if (f > top_force - 0.5) break;
    auto k = [&](int r, int c) { return slope_at_force(at.at({r, c}), f); };
    auto law = [f](int r, int c) { return law_k_at_force(r, c, f, Law::sloped); };
    double shallow = 0, shallow_law = 0;
    for (int r = 4; r <= 6; ++r) {
      shallow += column_contrast(k, r, 5) / 3;
      shallow_law += column_contrast(law, r, 5) / 3;
    }
    std::printf("%5.2f  %6.1f%%  %6.1f%%  %6.1f%%  %6.1f%%   | %4.1f %4.1f %4.1f %%, %4.1f %%\n", f,
                100 * row_contrast(k, 2, 4), 100 * row_contrast(k, 5, 4),
                100 * row_contrast(k, 8, 4),
                100 * shallow, 100 * row_contrast(law, 2, 4), 100 * row_contrast(law, 5, 4),
                100 * row_contrast(law, 8, 4), 100 * shallow_law);
    for (int r : {2, 5, 8}) {
      EXPECT_NEAR(row_contrast(k, r, 4), row_contrast(law, r, 4), 0.01)
          << "row " << r << ", " << f << " N";
      EXPECT_LT(row_contrast(k, r, 4), 0.10) << "row " << r << ", " << f << " N";
    }
    EXPECT_NEAR(shallow, shallow_law, 0.03) << f << " N";
  }
  EXPECT_GT(top_force, 7.0);  // the clamp's 3.2 A gives 7.88 N less k_v times the depth
}

// The map's own k_fd (0.25-0.75 mm, about 1-2 N on the pad) already holds the deep rows, 4-5 %
// below the median row, where the other rows lie within -1.1 .. +2.5 % of it (palp-sim, run to
// run +-0.3 %: the robot's wall-clock holds): a 3 % threshold finds them as the only soft rows,
// the default 10 % finds none. Column 4 (off the shallow channels), rows 1-9, the 2D protocol.
TEST(DepthSensitivity, KfdMapFindsTheDeepRowsAtAThreePercentThresholdNotAtTen) {
  palp::sim::InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  palp::Plan plan = palp::trace_test::pad_plan(9);
  plan.grid.columns = 1;
  plan.grid.x0_m = 0.040;
  plan.grid.pitch_x_m = plan.grid.pitch_y_m = 0.010;
  const auto dir = std::filesystem::temp_directory_path() /
                   ("palp_depth_kfd_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  palp::MapOptions o;
  o.settings.repetitions = 1;
  const palp::StiffnessMap m =
      palp::map_plan(probe, *robot, palp::trace_test::sim_rig(sim), plan, dir, o);
  ASSERT_TRUE(m.complete) << m.stopped_because;
  const palp::MapAnalysis a = palp::analyze_map(m, 0.03);
  std::printf("k_fd map, column 4: row vs median row");
  for (int r = 0; r < 9; ++r)
    std::printf(" %+.1f%%", 100 * (a.row_mean_N_per_m[static_cast<std::size_t>(r)] /
                                   a.median_N_per_m - 1));
  std::printf("\n");
  EXPECT_EQ(a.soft_rows, (std::vector<int>{2, 5, 8}));
  EXPECT_TRUE(palp::analyze_map(m, 0.1).soft_rows.empty());
  std::filesystem::remove_all(dir);
}

}  // namespace depth_sensitivity_test
