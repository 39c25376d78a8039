// SPDX-License-Identifier: Apache-2.0
// palp-report-sim-map OUT_DIR: a real map for the report's page test, the demo's in small: palp-sim
// linked in (virtual time) with the 2D pad under the probe, rows 1..3 of the paper's 9 x 9 grid
// (all nine columns, so the soft channels under columns 2, 5 and 8 are crossed), one repetition
// of a ramp to 1.5 A a point; then the map's report as OUT_DIR/map-report.html. Nothing here is
// synthetic: the stiffness the page must show comes from the plant's pad and the real firmware
// core. OUT_DIR is replaced. With --adaptive the same rows are mapped adaptively (14 of the 27
// points: the coarse design's 9, one per column, then refinement; palp/analysis/adaptive_grid.hpp)
// for the report's irregular heat map.
#include <filesystem>
#include <iostream>
#include <string>

#include "palp/map.hpp"
#include "palp/probe.hpp"
#include "palp/report.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"
#include "trace_sim.hpp"

int main(int argc, char** argv) {
  const bool adaptive = argc == 3 && std::string(argv[2]) == "--adaptive";
  if (argc != 2 && !adaptive) {
    std::cerr << "usage: palp-report-sim-map OUT_DIR [--adaptive]\n";
    return 2;
  }
  namespace fs = std::filesystem;
  const fs::path out = argv[1];
  try {
    fs::remove_all(out);
    fs::create_directories(out);
    palp::sim::InprocSimulator sim({.phantom = "pad_2d", .robot = true});
    palp::Probe probe(sim.transport());
    auto robot = palp::connect_robot(sim.robot_uri());
    palp::Rig rig = palp::trace_test::sim_rig(sim);
    rig.safe_height_m = 5e-3;  // the pad's crests are flat at z = -1.5 mm: no tilted plane here
    palp::Plan plan = palp::trace_test::pad_plan(9);
    plan.grid.rows = 3;
    palp::MapOptions o;
    o.settings.repetitions = 1;
    o.settings.stop_A = 1.5;
    if (adaptive) o.adaptive = palp::analysis::AdaptiveGridOptions{.max_points = 14};
    const palp::StiffnessMap m = palp::map_plan(probe, *robot, rig, plan, out / "map", o);
    if (!m.complete) {
      std::cerr << "palp-report-sim-map: the map stopped: " << m.stopped_because << "\n";
      return 1;
    }
    palp::report::write_report_html(out / "map-report.html", palp::report::make_report(out / "map"));
    std::cout << (out / "map-report.html").string() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "palp-report-sim-map: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
