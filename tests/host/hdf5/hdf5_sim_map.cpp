// SPDX-License-Identifier: Apache-2.0
// palp-hdf5-sim-map DIR [N REPS STOP_A]: maps an N x N grid (2) of the pad phantom on palp-sim
// linked in (virtual time; REPS repetitions (2) of a ramp to STOP_A (1.5 A) a point) into DIR/map
// and exports it as DIR/map.h5, for the independent reader (check_h5py_map.py compares the file
// with the directory's map.json and CSVs). `DIR 9 3 3` is the paper's 9 x 9 map, for its size.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <numbers>

#include "palp/hdf5.hpp"
#include "palp/map.hpp"
#include "palp/probe.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"

int main(int argc, char** argv) {
  if (argc != 2 && argc != 5) {
    std::fprintf(stderr, "usage: palp-hdf5-sim-map DIR [N REPS STOP_A]\n");
    return 2;
  }
  const int n = argc == 5 ? std::atoi(argv[2]) : 2, reps = argc == 5 ? std::atoi(argv[3]) : 2;
  const double stop_A = argc == 5 ? std::atof(argv[4]) : 1.5;
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::remove_all(dir / "map");
    palp::sim::InprocSimulator sim({.phantom = "pad_2d", .robot = true});
    palp::Probe probe(sim.transport());
    auto robot = palp::connect_robot(sim.robot_uri());
    palp::Rig rig;  // as tests/host/sim/test_map.cpp places the pad
    rig.robot_uri = sim.robot_uri();
    rig.probe_uri = sim.uri();
    rig.tool_tcp = palp::Pose{0, 0, 0.200, 0, 0, 0};
    rig.safe_height_m = 5e-3;
    rig.travel_speed_m_per_s = 0.05;
    rig.work_object = palp::WorkObject{"pad", palp::Pose{0.600, 0.0, 0.300, 0, 0, std::numbers::pi}};
    palp::Plan plan;
    plan.name = "pad";
    plan.work_object = "pad";
    plan.grid.rows = plan.grid.columns = n;
    plan.grid.x0_m = 0.010;
    plan.grid.y0_m = 0.005;
    plan.grid.pitch_x_m = plan.grid.pitch_y_m = n == 2 ? 0.030 : 0.010;
    plan.contact_E_star_Pa = 3.3e6;
    palp::MapOptions o;
    o.settings.repetitions = reps;
    o.settings.stop_A = stop_A;  // 1.5 A: a short ramp
    const palp::StiffnessMap m = palp::map_plan(probe, *robot, rig, plan, dir / "map", o);
    if (!m.complete) {
      std::fprintf(stderr, "palp-hdf5-sim-map: the map stopped: %s\n", m.stopped_because.c_str());
      return 1;
    }
    palp::write_map_hdf5(dir / "map.h5", palp::load_map_results(dir / "map"), palp::Overwrite::yes);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palp-hdf5-sim-map: %s\n", e.what());
    return 1;
  }
  return 0;
}
