// SPDX-License-Identifier: Apache-2.0
// The binding's parts, one function per file, called by module.cpp in this order.
#pragma once

#include "convert.hpp"
#include "palp/probe.hpp"
#include "palp/robot.hpp"

namespace palp_python {

/// The holder of an object whose destructor joins an SDK thread that may be waiting for the GIL
/// (to call the log handler, log.cpp): the destructor runs with the GIL released so that thread
/// can finish.
template <class T>
struct ReleasingDelete {
  void operator()(T* p) const {
    py::gil_scoped_release unlocked;
    delete p;
  }
};
using ProbeHolder = std::unique_ptr<palp::Probe, ReleasingDelete<palp::Probe>>;
using RobotHolder = std::unique_ptr<palp::Robot, ReleasingDelete<palp::Robot>>;
using RobotClass = py::class_<palp::Robot, RobotHolder>;

void bind_errors(py::module_& m);       ///< errors.cpp: palp.Error and its subclasses
void bind_messages(py::module_& m);     ///< messages.cpp: Params, Calibration, the programs
void bind_probe(py::module_& m);        ///< probe.cpp: palp.Probe, list_devices
void bind_stream(py::module_& m);       ///< stream.cpp: sample and gap dtypes, Probe.read
void bind_experiments(py::module_& m);  ///< experiments.cpp: indent and its settings and run
void bind_identification(py::module_& m);  ///< identification.cpp: identify, its settings and run
void bind_record(py::module_& m);       ///< record.cpp: record, the SDK recorder
void bind_analysis(py::module_& m);     ///< analysis.cpp: recordings and the offline analysis
void bind_robot(py::module_& m);        ///< robot.cpp: Robot, rig and plan files, maps
/// robot_motion.cpp: Pose, the robot's status and motions one by one (called by bind_robot)
void bind_robot_motions(py::module_& m, RobotClass& robot);
void bind_trace(py::module_& m);        ///< trace.cpp: trace, save_trace, load_trace
void bind_calibration(py::module_& m);  ///< calibration.cpp: calibrate_kf, its settings and run
void bind_log(py::module_& m);          ///< log.cpp: set_log_handler

}  // namespace palp_python
