// SPDX-License-Identifier: Apache-2.0
// Adaptive maps (issue 24) of the pad on palp-sim linked in, in virtual time: the soft columns
// found with at most 40 of the 81 points, and a stopped adaptive map that resumes with the
// planner's decisions from what its map.json holds.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "palp/analysis/adaptive_grid.hpp"
#include "palp/error.hpp"
#include "palp/map.hpp"
#include "palp/probe.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"
#include "palp/tidy_csv.hpp"
#include "sanitized.hpp"
#include "trace_sim.hpp"

namespace {

using palp::sim::InprocSimulator;

palp::Rig adaptive_pad_rig(const InprocSimulator& sim) {
  palp::Rig rig = palp::trace_test::sim_rig(sim);
  rig.safe_height_m = 5e-3;  // the pad's crests are flat at z = -1.5 mm
  return rig;
}

std::filesystem::path adaptive_fresh_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d;
}

/// Every point of `m` is the one the planner chooses after the points before it, as map.json
/// holds them (load_map): the decisions a resumed map makes again.
void expect_planner_order(const palp::StiffnessMap& m) {
  ASSERT_TRUE(m.adaptive.has_value());
  std::vector<palp::analysis::MeasuredCell> before;
  for (const palp::MapPoint& p : m.points) {
    const auto s = palp::analysis::next_adaptive_point(m.rows, m.columns, *m.adaptive, before);
    ASSERT_TRUE(s.next.has_value())
        << "after " << before.size() << " points the planner is done (" << s.phase << ")";
    EXPECT_EQ(*s.next, (palp::analysis::GridCell{p.row, p.column})) << "point " << before.size();
    before.push_back({p.row, p.column, p.k_fd_N_per_m});
  }
}

TEST(MapAdaptive, ThePadsSoftColumns258AreFoundWithAtMostFortyOfTheEightyOnePoints) {
  if (palp::sim::test::kSanitized)
    GTEST_SKIP() << "40 indentations of 12.5 s device time: the release build runs it";
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = adaptive_fresh_dir("palp_map_adaptive");
  palp::MapOptions o;  // the 2D protocol with one repetition, as the full 9 x 9 test (test_map.cpp)
  o.settings.repetitions = 1;
  o.adaptive = palp::analysis::AdaptiveGridOptions{};  // half the grid (40), 10 %, 9 coarse points
  const double t0 = sim.virtual_s();
  const palp::StiffnessMap m =
      palp::map_plan(probe, *robot, adaptive_pad_rig(sim), palp::trace_test::pad_plan(9), dir, o);
  const double device_s = sim.virtual_s() - t0;
  ASSERT_TRUE(m.complete) << m.stopped_because;
  EXPECT_LE(m.points.size(), 40u);
  const palp::MapAnalysis a = palp::analyze_map(m, 0.1);
  EXPECT_EQ(a.soft_columns, (std::vector<int>{2, 5, 8}));
  EXPECT_TRUE(a.soft_rows.empty());
  EXPECT_TRUE(a.stiff_columns.empty());
  // each soft column's mean against its neighbours' (the full map's test asks >= 20 % per point)
  double contrast = 1.0;
  for (int c : {2, 5, 8}) {
    const auto mean = [&](int k) { return a.column_mean_N_per_m[static_cast<std::size_t>(k - 1)]; };
    contrast = std::min(contrast, 1.0 - mean(c) / (0.5 * (mean(c - 1) + mean(c + 1))));
  }
  EXPECT_GE(contrast, 0.20);
  const palp::StiffnessMap back = palp::load_map(dir);
  expect_planner_order(back);
  const double per_point = device_s / static_cast<double>(m.points.size());
  std::printf(
      "adaptive 9 x 9: %zu of 81 points (%s), device time %.0f s (%.1f s a point); the full grid "
      "at that rate %.0f s: %.0f s (%.0f %%) saved; soft columns' contrast (min) %.1f %%\n",
      m.points.size(), m.adaptive_ended.c_str(), device_s, per_point, 81 * per_point,
      (81 - static_cast<double>(m.points.size())) * per_point,
      100.0 * (81 - static_cast<double>(m.points.size())) / 81, 100 * contrast);
  std::filesystem::remove_all(dir);
}

TEST(MapAdaptive, AStoppedAdaptiveMapResumesWithThePlannersDecisionsAndRefusesOtherOptions) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = adaptive_fresh_dir("palp_map_adaptive_resume");
  palp::Plan plan = palp::trace_test::pad_plan(9);
  plan.grid.rows = 3;  // rows 1..3 across all nine columns
  palp::MapOptions o;
  o.settings.repetitions = 1;
  o.settings.stop_A = 1.5;  // a short ramp: this test is about the bookkeeping
  o.adaptive = palp::analysis::AdaptiveGridOptions{.max_points = 13};
  std::size_t done = 0;
  o.progress = [&](const palp::MapProgress& p) { done = p.done; };
  o.cancelled = [&] { return done >= 5; };
  const palp::StiffnessMap part =
      palp::map_plan(probe, *robot, adaptive_pad_rig(sim), plan, dir, o);
  EXPECT_FALSE(part.complete);
  EXPECT_EQ(part.stopped_because, "cancelled");
  ASSERT_EQ(part.points.size(), 5u);
  // other options are refused before anything moves, naming both
  o.cancelled = {};
  o.resume = true;
  o.adaptive->threshold = 0.2;
  try {
    palp::map_plan(probe, *robot, adaptive_pad_rig(sim), plan, dir, o);
    ADD_FAILURE() << "resumed with another threshold";
  } catch (const palp::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "map.json").string() +
                  ": an adaptive map with max_points 13, threshold 0.1, coarse_points 9; it "
                  "resumes with the same options (or none), not max_points 13, threshold "
                  "0.2, coarse_points 9");
  }
  o.adaptive.reset();  // none: as map.json says
  const palp::StiffnessMap whole =
      palp::map_plan(probe, *robot, adaptive_pad_rig(sim), plan, dir, o);
  ASSERT_TRUE(whole.complete) << whole.stopped_because;
  ASSERT_TRUE(whole.adaptive.has_value());
  EXPECT_EQ(whole.adaptive->max_points, 13);
  EXPECT_LE(whole.points.size(), 13u);
  for (std::size_t k = 0; k < 5; ++k) {  // the first five kept, as they were
    EXPECT_EQ(whole.points[k].row, part.points[k].row);
    EXPECT_EQ(whole.points[k].column, part.points[k].column);
  }
  const palp::StiffnessMap back = palp::load_map(dir);
  EXPECT_EQ(back.adaptive_ended, whole.adaptive_ended);
  expect_planner_order(back);
  for (const palp::MapPoint& p : back.points) {
    EXPECT_TRUE(p.indented) << p.reason;
    EXPECT_TRUE(std::filesystem::exists(dir / p.result_dir / "result.json")) << p.result_dir;
  }
  // the coarse design covered all nine columns and all three rows first
  std::set<int> rows, columns;
  for (std::size_t k = 0; k < 9; ++k)
    rows.insert(back.points[k].row), columns.insert(back.points[k].column);
  EXPECT_EQ(rows.size(), 3u);
  EXPECT_EQ(columns.size(), 9u);
  // the tidy CSV: a row for every grid point, the ones not chosen saying so
  const palp::TidyCsvExport e = palp::export_tidy_csv(dir, dir / "export" / "map.csv");
  EXPECT_EQ(e.points, 27u);
  EXPECT_EQ(e.rows, 27u);  // one repetition a measured point, one row an unmeasured one
  std::ifstream in(dir / "export" / "map.csv");
  std::size_t not_chosen = 0;
  for (std::string line; std::getline(in, line);)
    not_chosen +=
        line.find("not measured: the adaptive map did not choose this point") != std::string::npos;
  EXPECT_EQ(not_chosen, 27 - back.points.size());
  std::filesystem::remove_all(dir);
}

}  // namespace
