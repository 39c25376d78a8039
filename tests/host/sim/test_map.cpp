// SPDX-License-Identifier: Apache-2.0
// The 2D study (issue 6's acceptance, paper §V): a 9 x 9 stiffness map of the pad on palp-sim
// linked in (palp/sim_inproc.hpp), with the arm placing the probe, in virtual time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "palp/analysis/pressure.hpp"
#include "palp/map.hpp"
#include "palp/result.hpp"
#include "palp/probe.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"
#include "palp/tidy_csv.hpp"
#include "sanitized.hpp"

namespace {

using palp::sim::InprocSimulator;
constexpr double kDeg = std::numbers::pi / 180.0;

palp::Rig pad_rig(const InprocSimulator& sim) {
  palp::Rig rig;
  rig.robot_uri = sim.robot_uri();
  rig.probe_uri = sim.uri();
  rig.tool_tcp = palp::Pose{0, 0, 0.200, 0, 0, 0};
  rig.safe_height_m = 5e-3;
  rig.travel_speed_m_per_s = 0.05;
  rig.work_object = palp::WorkObject{"pad", palp::Pose{0.600, 0.0, 0.300, 0, 0, 180 * kDeg}};
  return rig;
}

palp::Plan pad_plan(int n, double pitch_m) {
  palp::Plan plan;
  plan.name = "pad";
  plan.work_object = "pad";
  plan.grid.rows = plan.grid.columns = n;
  plan.grid.x0_m = 0.010;
  plan.grid.y0_m = 0.005;
  plan.grid.pitch_x_m = plan.grid.pitch_y_m = pitch_m;
  plan.contact_E_star_Pa = 3.3e6;
  return plan;
}

std::filesystem::path fresh_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d;
}

double k_at(const palp::MapAnalysis& a, int row, int column) {
  const auto& v = a.k_N_per_m[static_cast<std::size_t>((row - 1) * a.columns + column - 1)];
  EXPECT_TRUE(v.has_value()) << "no stiffness at row " << row << ", column " << column;
  return v.value_or(std::nan(""));
}

using palp::sim::test::kSanitized;

TEST(Map, NineByNinePadShowsTheShallowChannelColumnsSofterAndTheDeepChannelRowsNot) {
  if (kSanitized) GTEST_SKIP() << "81 indentations of 37.5 s device time: the release build runs it";
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = fresh_dir("palp_map_9x9");
  // the 2D protocol with one repetition instead of three (the test's time: 81 x 12.5 s of
  // device time; the three-repetition map is scripts/demo's, and bench_map times its analysis)
  palp::MapOptions o;
  o.settings.repetitions = 1;
  const palp::StiffnessMap m = palp::map_plan(probe, *robot, pad_rig(sim), pad_plan(9, 0.010), dir, o);
  ASSERT_TRUE(m.complete) << m.stopped_because;
  const palp::MapAnalysis a = palp::analyze_map(m, 0.2);
  // every row: columns 2, 5, 8 (over the shallow channels) at least 20 % softer than their neighbours
  double column_contrast = 1.0;
  for (int r = 1; r <= 9; ++r)
    for (int c : {2, 5, 8}) {
      const double ref = 0.5 * (k_at(a, r, c - 1) + k_at(a, r, c + 1));
      const double contrast = 1.0 - k_at(a, r, c) / ref;
      EXPECT_GE(contrast, 0.20) << "row " << r << ", column " << c;
      column_contrast = std::min(column_contrast, contrast);
    }
  // rows 2, 5, 8 (over the deep channels) differ from their neighbouring rows by less than half that
  for (int r : {2, 5, 8}) {
    const double ref = 0.5 * (a.row_mean_N_per_m[static_cast<std::size_t>(r - 2)] +
                              a.row_mean_N_per_m[static_cast<std::size_t>(r)]);
    const double diff = std::abs(1.0 - a.row_mean_N_per_m[static_cast<std::size_t>(r - 1)] / ref);
    EXPECT_LT(diff, 0.5 * column_contrast) << "row " << r;
  }
  EXPECT_EQ(a.soft_columns, (std::vector<int>{2, 5, 8}));
  EXPECT_TRUE(a.soft_rows.empty());
  // at row 8, column 8 channels 6 (shallow, under column 8) and 1 (deep, under row 8) rise
  // linearly with force, channel 6 2.5 to 4.5 times as much (paper §V-D)
  const palp::LoadedResult r88 = palp::load_result(dir / m.points[7 * 9 + 7].result_dir);
  ASSERT_FALSE(r88.recordings.empty());
  const palp::Recording& rec = r88.recordings.front().second;
  const palp::analysis::Curve curve = palp::curve_of(rec);
  Eigen::MatrixXd P(static_cast<Eigen::Index>(rec.t_s.size()), 6);
  for (std::size_t ch = 0; ch < 6; ++ch) {
    ASSERT_TRUE(rec.p_Pa[ch].has_value()) << "no p" << ch + 1 << "_Pa";
    for (std::size_t k = 0; k < rec.t_s.size(); ++k)
      P(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(ch)) = (*rec.p_Pa[ch])[k];
  }
  const palp::IndentationRun run88 = palp::indentation_run_of(r88);
  ASSERT_TRUE(run88.analysis && run88.analysis->contact_z_m.value);
  const auto pr = palp::analysis::analyze_pressure(curve, P, run88.settings.analysis,
                                                   *run88.analysis->contact_z_m.value);
  const auto& ch1 = pr.channels[0];
  const auto& ch6 = pr.channels[5];
  ASSERT_TRUE(ch1.fit.r2.value && ch6.fit.r2.value && ch1.rise_Pa.value && ch6.rise_Pa.value);
  EXPECT_GE(*ch6.fit.r2.value, 0.98);
  EXPECT_GE(*ch1.fit.r2.value, 0.98);
  const double ratio = *ch6.rise_Pa.value / *ch1.rise_Pa.value;
  EXPECT_GE(ratio, 2.5);
  EXPECT_LE(ratio, 4.5);
  std::printf("row 8, column 8: p6/p1 = %.2f, R2 %.4f and %.4f\n", ratio, *ch6.fit.r2.value, *ch1.fit.r2.value);
  // the map reloads as written
  const palp::StiffnessMap back = palp::load_map(dir);
  ASSERT_EQ(back.points.size(), 81u);
  ASSERT_TRUE(back.points[40].k_fd_N_per_m && m.points[40].k_fd_N_per_m);
  EXPECT_NEAR(*back.points[40].k_fd_N_per_m, *m.points[40].k_fd_N_per_m, 1e-9 * *m.points[40].k_fd_N_per_m);
  std::printf("column contrast (min over rows) %.1f %%\n", 100 * column_contrast);
  std::filesystem::remove_all(dir);
}

TEST(Map, CancelledMapResumesFromTheFirstUnfinishedPointWithoutRepeats) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = fresh_dir("palp_map_resume");
  palp::MapOptions o;
  o.settings.repetitions = 1;
  o.settings.stop_A = 1.5;  // a short ramp: this test is about the bookkeeping
  std::size_t done = 0;
  o.progress = [&](const palp::MapProgress& p) { done = p.done; };
  o.cancelled = [&] { return done >= 2; };
  const palp::Plan plan = pad_plan(2, 0.040);
  const palp::StiffnessMap part = palp::map_plan(probe, *robot, pad_rig(sim), plan, dir, o);
  EXPECT_FALSE(part.complete);
  EXPECT_EQ(part.stopped_because, "cancelled");
  EXPECT_EQ(part.resume_index, 2u);
  EXPECT_EQ(probe.status().i_cmd_A, 0.0);
  o.cancelled = {};
  o.resume = true;
  const palp::StiffnessMap whole = palp::map_plan(probe, *robot, pad_rig(sim), plan, dir, o);
  ASSERT_TRUE(whole.complete) << whole.stopped_because;
  ASSERT_EQ(whole.points.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(whole.points[k].row, static_cast<int>(k) / 2 + 1);
    EXPECT_EQ(whole.points[k].column, static_cast<int>(k) % 2 + 1);
    EXPECT_TRUE(whole.points[k].indented) << whole.points[k].reason;
    EXPECT_TRUE(std::filesystem::exists(dir / whole.points[k].result_dir / "result.json"));
  }
  for (std::size_t k = 0; k < 2; ++k) {  // kept (to the rounding of map.json's N/mm)
    ASSERT_TRUE(whole.points[k].k_fd_N_per_m && part.points[k].k_fd_N_per_m);
    EXPECT_NEAR(*whole.points[k].k_fd_N_per_m, *part.points[k].k_fd_N_per_m, 1e-9 * *part.points[k].k_fd_N_per_m);
  }
  std::filesystem::remove_all(dir);
}

// The tidy CSV of a map palp-sim made, read by an independent reader (Debian's Python, stdlib
// csv; /usr/bin/python3, not the python3 first on PATH): a row per repetition, and the spread of
// each point's per-repetition k_fd is the s.d. its result.json gives (the same repetitions, each
// analysed alone, again from what the directory holds: to 1e-6, as its lab-unit numbers can
// differ from the run's in their last bits and the s.d. of close values magnifies that).
TEST(Map, ItsTidyCsvHasARowPerRepetitionWhoseKfdSpreadIsTheResultsSd) {
  InprocSimulator sim({.phantom = "pad_2d", .robot = true});
  palp::Probe probe(sim.transport());
  auto robot = palp::connect_robot(sim.robot_uri());
  const auto dir = fresh_dir("palp_map_tidy_csv");
  palp::MapOptions o;
  o.settings.repetitions = 2;
  o.settings.stop_A = 1.5;  // a short ramp
  palp::Plan plan = pad_plan(1, 0.040);
  plan.grid.columns = 2;
  const palp::StiffnessMap m = palp::map_plan(probe, *robot, pad_rig(sim), plan, dir, o);
  ASSERT_TRUE(m.complete) << m.stopped_because;
  const std::filesystem::path csv = dir / "export" / "map.csv";
  const palp::TidyCsvExport e = palp::export_tidy_csv(dir, csv);
  EXPECT_EQ(e.rows, 4u);
  EXPECT_TRUE(e.damaged.empty());
  const std::filesystem::path script = dir / "export" / "read.py";
  std::ofstream(script) << R"(import csv, json, os, statistics, sys
with open(sys.argv[1], newline="") as f:
    rows = list(csv.DictReader(f))
points = []
for c in ("1", "2"):
    mine = [r for r in rows if r["row"] == "1" and r["column"] == c]
    with open(os.path.join(sys.argv[2], "points", "r1_c" + c, "result.json")) as f:
        result = json.load(f)
    points.append({"reps": [r["rep"] for r in mine],
                   "sd": statistics.stdev(float(r["k_fd_N_per_mm"]) for r in mine),
                   "result_sd": result["analysis"]["k_fd_N_per_mm_sd"]})
print(json.dumps({"rows": len(rows), "points": points}))
)";
  std::FILE* p = ::popen(("/usr/bin/python3 " + script.string() + " " + csv.string() + " " + dir.string()).c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  ASSERT_EQ(::pclose(p), 0) << out;
  const nlohmann::json py = nlohmann::json::parse(out);
  EXPECT_EQ(py["rows"], 4);
  for (const auto& point : py["points"]) {
    EXPECT_EQ(point["reps"], nlohmann::json::array({"0", "1"}));
    const double sd = point["sd"].get<double>(), want = point["result_sd"].get<double>();
    EXPECT_GT(want, 0.0);
    EXPECT_NEAR(sd, want, 1e-6 * want);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
