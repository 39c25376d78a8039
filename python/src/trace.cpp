// SPDX-License-Identifier: Apache-2.0
// Surface tracing (palp/trace.hpp): palp.trace(probe, robot, rig, plan) touches every point of the
// plan's grid with a guarded approach and returns the TracedSurface (contact points, normals and
// tilts in the work-object frame, SI); palp.save_trace / palp.load_trace are its trace.json.
// Ctrl-C during a trace: the SDK's `cancelled` turns true, the SDK stops the arm, leaves the coil
// at 0 A and raises the arm to the safe height; then KeyboardInterrupt is raised.
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "palp/trace.hpp"

namespace palp_python {

namespace {

palp::TracedSurface trace(palp::Probe& probe, palp::Robot& robot, const palp::Rig& rig, const palp::Plan& plan,
                          const py::object& progress, const std::optional<palp::TracedSurface>& resume) {
  Interrupt interrupt;
  palp::TraceOptions o;
  o.cancelled = interrupt.callback();
  o.resume = resume;
  if (!progress.is_none())
    o.progress = [&progress, &interrupt](const palp::TraceProgress& p) {
      interrupt.call(progress, p.done, p.total);  // a Ctrl-C inside it cancels, as poll() would
    };
  palp::TracedSurface s;
  {
    py::gil_scoped_release release;
    s = palp::trace_surface(probe, robot, rig, plan, o);
  }
  interrupt.rethrow_if_interrupted();
  if (s.stopped_error) std::rethrow_exception(s.stopped_error);
  return s;
}

}  // namespace

void bind_trace(py::module_& m) {
  using palp::TracePoint;
  using palp::TracedSurface;
  py::class_<TracePoint>(m, "TracePoint", "One traced grid point: the contact point in the work-object frame, SI.")
      .def_readonly("row", &TracePoint::row)
      .def_readonly("column", &TracePoint::column)
      .def_readonly("ok", &TracePoint::ok)
      .def_readonly("reason", &TracePoint::reason)
      .def_readonly("x_m", &TracePoint::x_m)
      .def_readonly("y_m", &TracePoint::y_m)
      .def_readonly("z_m", &TracePoint::z_m)
      .def_property_readonly(
          "apex_m", [](const TracePoint& p) { return py::make_tuple(p.apex_x_m, p.apex_y_m, p.apex_z_m); },
          "The tip apex at zero force (x, y, z).")
      .def_property_readonly(
          "normal", [](const TracePoint& p) { return py::make_tuple(p.normal[0], p.normal[1], p.normal[2]); },
          "Unit surface normal (x, y, z), into the specimen.")
      .def_readonly("tilt_rad", &TracePoint::tilt_rad)
      .def_readonly("indentation_m", &TracePoint::indentation_m)
      .def_readonly("stroke_at_rest_m", &TracePoint::stroke_at_rest_m)
      .def_readonly("detection_force_N", &TracePoint::detection_force_N)
      .def_readonly("contact_stiffness_N_per_m", &TracePoint::contact_stiffness_N_per_m)
      .def_readonly("overtravel_m", &TracePoint::overtravel_m);

  py::class_<TracedSurface>(m, "TracedSurface", "A traced grid and how it ended (trace.json).")
      .def_readonly("plan_name", &TracedSurface::plan_name)
      .def_readonly("rows", &TracedSurface::rows)
      .def_readonly("columns", &TracedSurface::columns)
      .def_readonly("tip_radius_m", &TracedSurface::tip_radius_m)
      .def_readonly("contact_E_star_Pa", &TracedSurface::contact_E_star_Pa)
      .def_readonly("points", &TracedSurface::points)
      .def_readonly("resume_index", &TracedSurface::resume_index)
      .def_readonly("complete", &TracedSurface::complete)
      .def_readonly("normals_from_grid", &TracedSurface::normals_from_grid)
      .def_readonly("stopped_because", &TracedSurface::stopped_because);

  m.def("trace", &trace, py::arg("probe"), py::arg("robot"), py::arg("rig"), py::arg("plan"),
        py::arg("progress") = py::none(), py::arg("resume") = std::nullopt,
        "Touches every point of the plan (palp/trace.hpp); progress(done, total); resume: a "
        "TracedSurface that stopped. An error that stopped it is raised (the arm made safe first). "
        "Ctrl-C: arm stopped and raised, coil at 0 A, KeyboardInterrupt.");
  m.def("save_trace", &palp::save_trace, py::arg("file"), py::arg("surface"),
        "Writes trace.json (lab units, atomically).");
  m.def("load_trace", &palp::load_trace, py::arg("file"), "Reads trace.json back (ConfigError naming the problem).");
}

}  // namespace palp_python
