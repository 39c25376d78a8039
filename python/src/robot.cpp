// SPDX-License-Identifier: Apache-2.0
// The robot and stiffness maps: palp.Robot(uri) (palp/robot.hpp), rig and plan files
// (palp/rig.hpp), palp.map_plan and palp.analyze_map (palp/map.hpp). Ctrl-C during a map: the
// SDK's `cancelled` turns true, the SDK stops the arm, leaves the coil at 0 A and raises the arm
// to the safe height, the map stays resumable in its directory; then KeyboardInterrupt is raised.
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "palp/map.hpp"
#include "palp/trace.hpp"
#include "palp/rig.hpp"
#include "palp/robot.hpp"

namespace palp_python {

namespace {

palp::StiffnessMap map_plan(palp::Probe& probe, palp::Robot& robot, const palp::Rig& rig,
                            const palp::Plan& plan, const std::filesystem::path& dir,
                            const std::optional<palp::IndentationSettings>& settings,
                            const py::object& progress, bool resume, bool adaptive, int max_points,
                            double threshold, std::optional<double> max_force_N, bool dynamic,
                            const std::string& align, const std::optional<std::filesystem::path>& trace) {
  Interrupt interrupt;
  palp::MapOptions o;
  if (settings) o.settings = *settings;
  o.resume = resume;
  if (adaptive) {
    palp::analysis::AdaptiveGridOptions a;
    a.max_points = max_points;
    a.threshold = threshold;
    o.adaptive = a;
  }
  o.max_force_N = max_force_N;
  o.dynamic.enabled = dynamic;
  if (align != "none" && align != "normal")
    throw palp::ConfigError("map_plan: align must be \"none\" or \"normal\" (got \"" + align + "\")");
  o.align_to_normal = align == "normal";
  if (trace) o.align_trace = palp::load_trace(*trace);
  o.cancelled = interrupt.callback();
  if (!progress.is_none())
    o.progress = [&progress, &interrupt](const palp::MapProgress& p) {
      interrupt.call(progress, p.done, p.total, p.phase);
    };
  palp::StiffnessMap m;
  {
    py::gil_scoped_release release;
    m = palp::map_plan(probe, robot, rig, plan, dir, o);
  }
  interrupt.rethrow_if_interrupted();
  if (m.stopped_error) std::rethrow_exception(m.stopped_error);
  return m;
}

}  // namespace

void bind_robot(py::module_& m) {
  RobotClass robot(m, "Robot", "The robot bridge client (modbus://host:port).");
  robot.def(py::init([](const std::string& uri) {
              py::gil_scoped_release release;
              return RobotHolder(palp::connect_robot(uri).release());
            }),
            py::arg("uri"),
            "Connects and checks the bridge's magic and version (RobotLinkError: unreachable).");
  bind_robot_motions(m, robot);

  py::class_<palp::Rig>(m, "Rig", "A rig file: the robot, the probe, the tool and the work object.")
      .def_readonly("robot_uri", &palp::Rig::robot_uri)
      .def_readonly("probe_uri", &palp::Rig::probe_uri)
      .def_readonly("safe_height_m", &palp::Rig::safe_height_m);
  m.def("load_rig", &palp::load_rig, py::arg("file"), "Reads a rig file (ConfigError naming the key).");

  py::class_<palp::Plan>(m, "Plan", "A plan file: the grid of points on the work object.")
      .def_readonly("name", &palp::Plan::name)
      .def_readonly("work_object", &palp::Plan::work_object)
      .def("point_count", &palp::Plan::point_count);
  m.def("load_plan", &palp::load_plan, py::arg("file"), "Reads a plan file (ConfigError naming the key).");

  py::class_<palp::StiffnessMap>(m, "StiffnessMap", "A map: its points and how it ended (map.json).")
      .def_readonly("plan_name", &palp::StiffnessMap::plan_name)
      .def_readonly("rows", &palp::StiffnessMap::rows)
      .def_readonly("columns", &palp::StiffnessMap::columns)
      .def_readonly("complete", &palp::StiffnessMap::complete)
      .def_readonly("stopped_because", &palp::StiffnessMap::stopped_because)
      .def("to_dict", [](const palp::StiffnessMap& s) { return to_python(palp::map_to_json(s)); },
           "map.json's document (map_to_json).");
  m.def("load_map", &palp::load_map, py::arg("dir"), "Reads a map directory's map.json.");

  py::class_<palp::MapAnalysis>(m, "MapAnalysis", "The stiffness grid and the lines that stand out.")
      .def_readonly("rows", &palp::MapAnalysis::rows)
      .def_readonly("columns", &palp::MapAnalysis::columns)
      .def_readonly("k_N_per_m", &palp::MapAnalysis::k_N_per_m)
      .def_readonly("column_mean_N_per_m", &palp::MapAnalysis::column_mean_N_per_m)
      .def_readonly("row_mean_N_per_m", &palp::MapAnalysis::row_mean_N_per_m)
      .def_readonly("median_N_per_m", &palp::MapAnalysis::median_N_per_m)
      .def_readonly("soft_columns", &palp::MapAnalysis::soft_columns)
      .def_readonly("stiff_columns", &palp::MapAnalysis::stiff_columns)
      .def_readonly("soft_rows", &palp::MapAnalysis::soft_rows)
      .def_readonly("stiff_rows", &palp::MapAnalysis::stiff_rows)
      .def_readonly("contrast", &palp::MapAnalysis::contrast);
  m.def("analyze_map", &palp::analyze_map, py::arg("map"), py::arg("contrast") = 0.1,
        "k per point and the soft/stiff rows and columns at `contrast` (0.1: 10 %).");

  m.def("map_plan", &map_plan, py::arg("probe"), py::arg("robot"), py::arg("rig"), py::arg("plan"),
        py::arg("dir"), py::arg("settings") = std::nullopt, py::arg("progress") = py::none(),
        py::arg("resume") = false, py::kw_only(), py::arg("adaptive") = false,
        py::arg("max_points") = 0, py::arg("threshold") = 0.1, py::arg("max_force_N") = std::nullopt,
        py::arg("dynamic") = false, py::arg("align") = "none", py::arg("trace") = std::nullopt,
        "Touches and indents every point of the plan into `dir` (palp/map.hpp); progress(done, "
        "total, phase). adaptive: only the points the planner chooses (max_points: the budget, 0 "
        "for half the grid; threshold: neighbours differing by more refine); max_force_N: each "
        "ramp's top for that object force; dynamic: identify the contact after every ramp; "
        "align='normal': the tool along the surface normal (from trace, a trace.json, else a "
        "local trace). Ctrl-C: arm stopped and raised, coil at 0 A, KeyboardInterrupt.");
}

}  // namespace palp_python
