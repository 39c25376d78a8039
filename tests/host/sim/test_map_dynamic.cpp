// SPDX-License-Identifier: Apache-2.0
// Viscoelastic maps (issue 24, map_dynamic.hpp): a 3 x 3 subset of the pad's grid on palp-sim
// linked in, quasi-static ramp then identification at every point, in virtual time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "palp/error.hpp"
#include "palp/plant/linearisation.hpp"
#include "palp/plant/phantom.hpp"
#include "palp/plant/plant.hpp"
#include "palp/map.hpp"
#include "palp/probe.hpp"
#include "palp/result.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"
#include "sanitized.hpp"
#include "trace_sim.hpp"

namespace {

using palp::sim::InprocSimulator;
using palp::sim::test::kSanitized;

/// Rows 4-6, columns first_column.. +2 of the pad's 9 x 9 grid.
palp::Plan pad_subset(int first_column) {
  palp::Plan plan = palp::trace_test::pad_plan(9);
  plan.grid.rows = plan.grid.columns = 3;
  plan.grid.x0_m += (first_column - 1) * plan.grid.pitch_x_m;
  plan.grid.y0_m += 3 * plan.grid.pitch_y_m;
  return plan;
}
/// Rows 4-6, columns 4-6: column 5 lies over a shallow channel (soft).
palp::Plan pad_centre_subset() { return pad_subset(4); }

std::filesystem::path dynamic_map_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d;
}

/// The plant as palp-sim builds it, linearised at the bias with the probe over the point (x, y)
/// of the phantom frame (the work object's) and its mount where the floating tip (I_c) touches.
palp::plant::Linearisation pad_reference(double x_m, double y_m, double bias_A, double ic_A) {
  palp::plant::Plant plant(palp::plant::PlantConfig{}, palp::plant::load_shipped_phantom("pad_2d"));
  const double s_float = palp::plant::linearise_free_air(palp::plant::PlantConfig{}, ic_A).stroke_m;
  plant.set_mount(x_m, y_m, plant.phantom()->surface_z_m(x_m, y_m) - s_float);
  return palp::plant::linearise(plant, bias_A);
}

palp::MapOptions dynamic_map_options() {
  palp::MapOptions o;
  o.settings.repetitions = 1;  // the test's time; the ramp is the 2D protocol's
  o.dynamic.enabled = true;
  return o;
}

void print_dynamic_grid(const palp::StiffnessMap& m) {
  const palp::MapAnalysis a = palp::analyze_map(m);
  const palp::MapDynamicGrids g = palp::map_dynamic_grids(m);
  for (int r = 0; r < m.rows; ++r)
    for (int c = 0; c < m.columns; ++c) {
      const auto at = static_cast<std::size_t>(r * m.columns + c);
      std::printf("r%d c%d k_fd %.4f N/mm", r + 1, c + 1, a.k_N_per_m[at].value_or(NAN) * 1e-3);
      for (std::size_t q = 0; q < palp::dynamic_quantities().size(); ++q)
        std::printf(" %s %.5g (se %.2g)", palp::dynamic_quantities()[q].key,
                    g.value[q][at].value_or(NAN), g.se[q][at].value_or(NAN));
      std::printf("\n");
    }
}

TEST(MapDynamic, ThreeByThreePadSubsetGivesEveryPointsDynamicsAndTheSoftColumnTheLowestOmegaN) {
  if (kSanitized) GTEST_SKIP() << "9 indentations and identifications: the release build runs it";
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = dynamic_map_dir("palp_map_dynamic");
  const palp::StiffnessMap m = palp::map_plan(probe, *robot, palp::trace_test::sim_rig(sim),
                                              pad_centre_subset(), dir, dynamic_map_options());
  ASSERT_TRUE(m.complete) << m.stopped_because;
  print_dynamic_grid(m);
  // every point within the accuracy of the plant's linearisation there: omega_n 0.5 %,
  // zeta 5 % (measured with contact_multisine_fast on the viscoelastic, oblique-contact pad: 0.11 %
  // and 0.9 %)
  const palp::Plan plan = pad_centre_subset();
  ASSERT_EQ(m.points.size(), 9u);
  for (const palp::MapPoint& p : m.points) {
    ASSERT_FALSE(p.dynamic_dir.empty()) << p.dynamic.reason;
    ASSERT_TRUE(p.dynamic.omega_n_rad_per_s && p.dynamic.zeta && p.dynamic.m_eff_kg &&
                p.dynamic.b_o_N_s_per_m && p.dynamic.E_storage_Pa && p.dynamic.E_loss_Pa)
        << "row " << p.row << ", column " << p.column << ": " << p.dynamic.reason;
    for (const palp::DynamicQuantity& q : palp::dynamic_quantities())
      EXPECT_GT((p.dynamic.*q.se).value_or(0), 0) << q.key << " has no standard error";
    const auto ref = pad_reference(plan.x_m(p.column - 1), plan.y_m(p.row - 1), 1.0, 0.5);
    const double e_w = *p.dynamic.omega_n_rad_per_s / ref.omega_n_rad_per_s - 1;
    const double e_z = *p.dynamic.zeta / ref.zeta - 1;
    std::printf(
        "r%d c%d: omega_n %.3f rad/s (plant %.3f, %+.3f %%), zeta %.4f (plant %.4f, %+.2f %%), "
        "m_eff %.4f kg (plant m %.4f kg)\n",
        p.row, p.column, *p.dynamic.omega_n_rad_per_s, ref.omega_n_rad_per_s, 100 * e_w,
        *p.dynamic.zeta, ref.zeta, 100 * e_z, *p.dynamic.m_eff_kg, ref.m_kg);
    EXPECT_LT(std::abs(e_w), 0.005) << "row " << p.row << ", column " << p.column;
    EXPECT_LT(std::abs(e_z), 0.05) << "row " << p.row << ", column " << p.column;
  }
  // the soft column (5 of the pad, the subset's 2) has the lowest omega_n of its row
  const palp::MapDynamicGrids g = palp::map_dynamic_grids(m);
  EXPECT_EQ(g.points_identified, 9u);
  for (int r = 0; r < 3; ++r) {
    const auto w = [&](int c) {
      return g.value[0][static_cast<std::size_t>(r * 3 + c)].value_or(NAN);
    };
    EXPECT_LT(w(1), 0.9 * std::min(w(0), w(2))) << "row " << r + 1;
  }
  // offline: each point's identification re-analysed from its recording gives the map's numbers,
  // and map.json reads back with them
  const palp::StiffnessMap back = palp::load_map(dir);
  ASSERT_EQ(back.points.size(), m.points.size());
  ASSERT_TRUE(back.dynamic.has_value());
  for (std::size_t k = 0; k < m.points.size(); ++k) {
    const palp::MapPoint& p = back.points[k];
    palp::IndentationRun ind = palp::indentation_run_of(palp::load_result(dir / p.result_dir));
    palp::analyze_run(ind);
    const palp::DynamicPoint again = palp::reanalyse_dynamic_point(
        palp::load_result(dir / p.dynamic_dir), ind.analysis ? &*ind.analysis : nullptr,
        ind.settings.analysis);
    for (const palp::DynamicQuantity& q : palp::dynamic_quantities()) {
      const double want = (m.points[k].dynamic.*q.value).value_or(NAN);
      EXPECT_NEAR((p.dynamic.*q.value).value_or(NAN), want, 1e-12 * std::abs(want))
          << q.key << " in map.json";
      EXPECT_NEAR((again.*q.value).value_or(NAN), want, 1e-9 * std::abs(want))
          << q.key << " re-analysed";
    }
  }
  std::printf("virtual time %.1f s\n", sim.virtual_s());
  std::filesystem::remove_all(dir);
}

TEST(MapDynamic, AnIdentificationAtAnotherBiasThanTheAnalysisIsRefusedBeforeAnythingMoves) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = dynamic_map_dir("palp_map_dynamic_bias");
  palp::MapOptions o = dynamic_map_options();
  o.dynamic.settings = palp::map_dynamic_settings(o.settings);
  o.dynamic.settings->bias_A = 1.2;
  const palp::Pose before = robot->pose();
  try {
    palp::map_plan(probe, *robot, palp::trace_test::sim_rig(sim), pad_centre_subset(), dir, o);
    FAIL() << "a 1.2 A identification was accepted for a 1.0 A analysis";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(
        e.what(),
        "dynamic map: the identification's bias 1.2 A is not the indentation analysis' I_0 "
        "1 A (k_o and delta0 would be at another operating point)");
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
  EXPECT_EQ(robot->pose().z_m, before.z_m) << "the arm moved";
  EXPECT_EQ(probe.status().i_cmd_A, 0.0) << "the coil carries current";
}

TEST(MapDynamic, ResumingADynamicMapWithoutTheDynamicOptionIsRefusedNamingIt) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = dynamic_map_dir("palp_map_dynamic_resume");
  palp::StiffnessMap begun;  // a dynamic map stopped before its first point
  begun.rows = begun.columns = begun.surface.rows = begun.surface.columns = 3;
  begun.dynamic = palp::map_dynamic_settings(begun.settings);
  palp::save_map(dir, begun);
  palp::MapOptions o;
  o.resume = true;
  try {
    palp::map_plan(probe, *robot, palp::trace_test::sim_rig(sim), pad_centre_subset(), dir, o);
    FAIL() << "a dynamic map was resumed quasi-statically";
  } catch (const palp::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "map.json").string() + ": a dynamic map: resume it with the dynamic option");
  }
  o.dynamic.enabled = true;
  o.settings.repetitions = 1;
  o.settings.stop_A = 1.5;            // a short ramp: this test is about the bookkeeping
  o.cancelled = [] { return true; };  // resumes (accepted), then stops at once
  const palp::StiffnessMap m =
      palp::map_plan(probe, *robot, palp::trace_test::sim_rig(sim), pad_centre_subset(), dir, o);
  EXPECT_EQ(m.stopped_because, "cancelled");
  EXPECT_TRUE(m.dynamic.has_value());
  std::filesystem::remove_all(dir);
}

/// A dynamic 3 x 3 map of `phantom` over `plan` (one ramp repetition), complete.
palp::StiffnessMap dynamic_map_of(const char* phantom, const palp::Plan& plan,
                                  const std::filesystem::path& dir) {
  InprocSimulator sim({.phantom = phantom, .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  palp::StiffnessMap m = palp::map_plan(probe, *robot, palp::trace_test::sim_rig(sim), plan, dir,
                                        dynamic_map_options());
  EXPECT_TRUE(m.complete) << phantom << ": " << m.stopped_because;
  std::filesystem::remove_all(dir);
  return m;
}

TEST(MapDynamic, ADampingInclusionShowsInZetaBoAndELossAndNotInKfd) {
  if (kSanitized) GTEST_SKIP() << "two 3 x 3 dynamic maps: the release build runs it";
  // pad_2d_damping: the pad with the Kelvin-Voigt tau doubled in a 12 mm disc around row 5,
  // column 4 (grid points (5, 4) and its 4-neighbours inside, the diagonals outside); rows 4-6,
  // columns 3-5 of it against the same points of the pad
  const palp::Plan plan = pad_subset(3);
  const palp::StiffnessMap pad =
      dynamic_map_of("pad_2d", plan, dynamic_map_dir("palp_map_dynamic_pad"));
  const palp::StiffnessMap inc =
      dynamic_map_of("pad_2d_damping", plan, dynamic_map_dir("palp_map_dynamic_damping"));
  ASSERT_EQ(pad.points.size(), 9u);
  ASSERT_EQ(inc.points.size(), 9u);
  for (std::size_t k = 0; k < 9; ++k) {
    const palp::MapPoint& a = pad.points[k];
    const palp::MapPoint& b = inc.points[k];
    ASSERT_TRUE(a.k_fd_N_per_m && b.k_fd_N_per_m && a.dynamic.zeta && b.dynamic.zeta &&
                a.dynamic.b_o_N_s_per_m && b.dynamic.b_o_N_s_per_m && a.dynamic.E_loss_Pa &&
                b.dynamic.E_loss_Pa && a.dynamic.omega_n_rad_per_s && b.dynamic.omega_n_rad_per_s)
        << "row " << a.row << ", column " << a.column;
    const int row = a.row + 3, column = a.column + 2;  // on the pad's grid
    const bool inside = std::abs(row - 5) + std::abs(column - 4) <= 1;
    const double k_fd = *b.k_fd_N_per_m / *a.k_fd_N_per_m, zeta = *b.dynamic.zeta / *a.dynamic.zeta;
    const double b_o = *b.dynamic.b_o_N_s_per_m / *a.dynamic.b_o_N_s_per_m;
    const double E_loss = *b.dynamic.E_loss_Pa / *a.dynamic.E_loss_Pa;
    const double w = *b.dynamic.omega_n_rad_per_s / *a.dynamic.omega_n_rad_per_s;
    std::printf(
        "pad (%d, %d) %s: damping / pad: k_fd %.4f, omega_n %.4f, zeta %.3f, b_o %.3f, E'' %.3f\n",
        row, column, inside ? "inside " : "outside", k_fd, w, zeta, b_o, E_loss);
    EXPECT_NEAR(k_fd, 1.0, 0.01) << "k_fd at (" << row << ", " << column << ")";
    EXPECT_NEAR(w, 1.0, 0.01) << "omega_n at (" << row << ", " << column << ")";
    if (inside) {
      EXPECT_GT(zeta, 1.5) << "(" << row << ", " << column << ")";
      EXPECT_GT(b_o, 1.5) << "(" << row << ", " << column << ")";
      EXPECT_GT(E_loss, 1.5) << "(" << row << ", " << column << ")";
    } else {
      // the same material: equal within 2 % or four of the ratio's standard errors (E'' carries
      // ~1 % from the lines' noise on each side, so a ratio 2 % off is only 1.4 sigma)
      const auto tolerance = [](const std::optional<double>& va, const std::optional<double>& sa,
                                const std::optional<double>& vb, const std::optional<double>& sb) {
        if (!sa || !sb) return 0.02;
        return std::max(0.02, 4 * std::hypot(*sa / *va, *sb / *vb));
      };
      EXPECT_NEAR(zeta, 1.0, tolerance(a.dynamic.zeta, a.dynamic.zeta_se, b.dynamic.zeta,
                                       b.dynamic.zeta_se))
          << "(" << row << ", " << column << ")";
      EXPECT_NEAR(E_loss, 1.0, tolerance(a.dynamic.E_loss_Pa, a.dynamic.E_loss_Pa_se,
                                         b.dynamic.E_loss_Pa, b.dynamic.E_loss_Pa_se))
          << "(" << row << ", " << column << ")";
    }
  }
}

}  // namespace
