// SPDX-License-Identifier: Apache-2.0
// The robot's motions one by one (palp/robot.hpp): palp.Pose, Robot.status() / pose(),
// move_lin, move_lin_rel, move_ptp, guarded_approach, stop, hold, set_tool, reset_fault. SI
// (m, rad, m/s, N, s); the bridge's enums (state, result, axis) as their map names (str).
// A motion releases the GIL and waits in slices: Ctrl-C stops the arm (Robot.stop: it returns
// once the arm is stationary) and then raises KeyboardInterrupt.
#include <algorithm>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "palp/robot.hpp"

namespace palp_python {

namespace {

namespace rb = palp::proto::rb;
using palp::Pose;
using palp::Robot;
using release = py::call_guard<py::gil_scoped_release>;

template <class E>
std::string rb_name(E value) {
  const char* n = rb::enum_name(value);
  return n ? n : "unknown (" + std::to_string(static_cast<unsigned>(value)) + ")";
}

template <class E>
E rb_of(const std::string& name, const char* what) {
  std::string names;
  for (const auto& v : rb::EnumInfo<E>::values) {
    if (name == v.name) return static_cast<E>(v.value);
    names += names.empty() ? "" : ", ";
    names += v.name;
  }
  throw palp::ConfigError(std::string(what) + ": unknown value \"" + name + "\" (one of " + names +
                          ")");
}

/// The GuardSource bits as their names (["digital_input"]).
std::vector<std::string> guard_names(std::uint16_t bits) {
  std::vector<std::string> out;
  for (const auto& v : rb::EnumInfo<rb::GuardSource>::values)
    if ((bits & (1u << v.value)) != 0) out.emplace_back(v.name);
  return out;
}

/// Waits for a motion in slices of at most 0.25 s, Ctrl-C checked between them: an interrupt
/// stops the arm and raises KeyboardInterrupt. A slice that ends while the finished motion still
/// brakes returns early (ModbusRobot::wait), so the wait goes on while the arm moves.
palp::MotionResult wait_motion(Robot& robot, palp::MotionHandle motion, double timeout_s) {
  Interrupt interrupt;
  const auto total = timeout_of(timeout_s);
  const auto end = std::chrono::steady_clock::now() + total;
  {
    py::gil_scoped_release unlocked;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      const bool last = left <= std::chrono::milliseconds(250);
      try {
        palp::MotionResult r = robot.wait(
            motion, std::clamp(left, std::chrono::milliseconds(1), std::chrono::milliseconds(250)));
        if (last || robot.status().state != rb::RobotState::moving) return r;
      } catch (const palp::TimeoutError& e) {
        if (last) throw palp::TimeoutError(e.waited_for(), timeout_s, e.health());
      }
      if (interrupt.poll()) {
        robot.stop();
        break;
      }
    }
  }
  interrupt.rethrow_if_interrupted();
  throw palp::Error("unreachable");  // poll() returned true, so rethrow raised
}

/// Starts a motion (GIL released) and waits for it as wait_motion does.
template <class Start>
palp::MotionResult run_motion(Robot& robot, const Start& start, double timeout_s) {
  palp::MotionHandle h;
  {
    py::gil_scoped_release unlocked;
    h = start();
  }
  return wait_motion(robot, h, timeout_s);
}

std::string pose_repr(const Pose& p) {
  return "Pose(x_m=" + std::to_string(p.x_m) + ", y_m=" + std::to_string(p.y_m) +
         ", z_m=" + std::to_string(p.z_m) + ", a_rad=" + std::to_string(p.a_rad) +
         ", b_rad=" + std::to_string(p.b_rad) + ", c_rad=" + std::to_string(p.c_rad) + ")";
}

}  // namespace

void bind_robot_motions(py::module_& m, RobotClass& robot) {
  py::class_<Pose>(m, "Pose",
                   "A TCP pose in the robot's base frame: x, y, z (m) and KUKA A, B, C (rad, ZYX).")
      .def(py::init([](double x, double y, double z, double a, double b, double c) {
             return Pose{x, y, z, a, b, c};
           }),
           py::arg("x_m") = 0.0, py::arg("y_m") = 0.0, py::arg("z_m") = 0.0, py::arg("a_rad") = 0.0,
           py::arg("b_rad") = 0.0, py::arg("c_rad") = 0.0)
      .def_readwrite("x_m", &Pose::x_m)
      .def_readwrite("y_m", &Pose::y_m)
      .def_readwrite("z_m", &Pose::z_m)
      .def_readwrite("a_rad", &Pose::a_rad)
      .def_readwrite("b_rad", &Pose::b_rad)
      .def_readwrite("c_rad", &Pose::c_rad)
      .def("__repr__", &pose_repr);

  py::class_<palp::RobotStatus>(m, "RobotStatus",
                                "One status snapshot of the bridge, SI; enums as their names.")
      .def_property_readonly("state", [](const palp::RobotStatus& s) { return rb_name(s.state); })
      .def_readonly("status_bits", &palp::RobotStatus::status_bits)
      .def_property_readonly("result", [](const palp::RobotStatus& s) { return rb_name(s.result); })
      .def_readonly("tool", &palp::RobotStatus::tool)
      .def_readonly("robot_time_s", &palp::RobotStatus::robot_time_s)
      .def_readonly("pose", &palp::RobotStatus::pose)
      .def_readonly("latched", &palp::RobotStatus::latched)
      .def_readonly("force_N", &palp::RobotStatus::force_N)
      .def_readonly("joints_rad", &palp::RobotStatus::joints_rad);

  py::class_<palp::GuardedApproach>(
      m, "GuardedApproach", "A linear motion along one axis until a guard fires or max travel.")
      .def(py::init<>())
      .def_property(
          "axis", [](const palp::GuardedApproach& g) { return rb_name(g.axis); },
          [](palp::GuardedApproach& g, const std::string& name) {
            g.axis = rb_of<rb::Axis>(name, "axis");
          },
          "\"tool_z\" (default: the probe's approach axis), tool_x, tool_y, base_x, base_y, "
          "base_z.")
      .def_readwrite("speed_m_per_s", &palp::GuardedApproach::speed_m_per_s)
      .def_readwrite("max_travel_m", &palp::GuardedApproach::max_travel_m,
                     "Signed: its sign is the direction along the axis.")
      .def_readwrite("guard_host_stop", &palp::GuardedApproach::guard_host_stop)
      .def_readwrite("digital_input", &palp::GuardedApproach::digital_input,
                     "1..16: the wired input (the probe's contact line is 1); 0: none.")
      .def_readwrite("force_threshold_N", &palp::GuardedApproach::force_threshold_N,
                     "The arm's own force guard; None: not armed.");

  py::class_<palp::MotionResult>(m, "MotionResult", "How a motion ended.")
      .def_readonly("seq", &palp::MotionResult::seq)
      .def_property_readonly(
          "result", [](const palp::MotionResult& r) { return rb_name(r.result); },
          "done, guard_fired, max_travel, stopped, superseded, ...")
      .def_property_readonly(
          "guard_fired", [](const palp::MotionResult& r) { return guard_names(r.guard_fired); },
          "The guards that fired: host_stop, digital_input, force.")
      .def_readonly("latched", &palp::MotionResult::latched,
                    "The pose when the stop or guard was taken.")
      .def_readonly("final_pose", &palp::MotionResult::final_pose, "Where the arm came to rest.");

  robot.def_property_readonly("uri", [](const Robot& r) { return r.info().uri; })
      .def("status", &Robot::status, release())
      .def("pose", &Robot::pose, release(), "The active tool's TCP in the base frame.")
      .def(
          "move_lin",
          [](Robot& r, const Pose& target, double speed_m_per_s, double timeout_s) {
            return run_motion(
                r, [&] { return r.start_move_lin(target, speed_m_per_s); }, timeout_s);
          },
          py::arg("target"), py::arg("speed_m_per_s"), py::arg("timeout_s") = 120.0,
          "A straight line to target; waits for it. Ctrl-C stops the arm and raises "
          "KeyboardInterrupt.")
      .def(
          "move_lin_rel",
          [](Robot& r, const Pose& offset, double speed_m_per_s, double timeout_s) {
            return run_motion(
                r, [&] { return r.start_move_lin_rel(offset, speed_m_per_s); }, timeout_s);
          },
          py::arg("offset"), py::arg("speed_m_per_s"), py::arg("timeout_s") = 120.0,
          "A straight line by offset, in the active tool's frame; waits as move_lin.")
      .def(
          "move_ptp",
          [](Robot& r, const Pose& target, double speed_fraction, double timeout_s) {
            return run_motion(
                r, [&] { return r.start_move_ptp(target, speed_fraction); }, timeout_s);
          },
          py::arg("target"), py::arg("speed_fraction"), py::arg("timeout_s") = 120.0,
          "A joint-space motion to target at speed_fraction (0, 1] of the joints' maximum; waits.")
      .def(
          "guarded_approach",
          [](Robot& r, const palp::GuardedApproach& g, double timeout_s) {
            return run_motion(
                r, [&] { return r.start_guarded_approach(g); }, timeout_s);
          },
          py::arg("approach"), py::arg("timeout_s") = 120.0,
          "Moves along the approach's axis until a guard fires (result \"guard_fired\") or its max "
          "travel (\"max_travel\"); waits. Ctrl-C stops the arm and raises KeyboardInterrupt.")
      .def(
          "stop", [](Robot& r, double timeout_s) { return r.stop(timeout_of(timeout_s)); },
          py::arg("timeout_s") = 2.0, release(), "Stops now; returns the status once stationary.")
      .def(
          "hold", [](Robot& r, double timeout_s) { r.hold(timeout_of(timeout_s)); },
          py::arg("timeout_s") = 2.0, release(), "Ends any motion and holds; waits for done.")
      .def("set_tool", &Robot::set_tool, py::arg("id"), py::arg("tcp_on_flange"), release(),
           "Makes tool id (1..15) active with its TCP frame relative to the flange.")
      .def("reset_fault", &Robot::reset_fault, release(),
           "Acknowledges a robot error (faulted -> idle).");
}

}  // namespace palp_python
