// SPDX-License-Identifier: Apache-2.0
// The binding's parts, one function per file, called by module.cpp in this order.
#pragma once

#include "convert.hpp"

namespace palp_python {

void bind_errors(py::module_& m);       ///< errors.cpp: palp.Error and its subclasses
void bind_messages(py::module_& m);     ///< messages.cpp: Params, Calibration, the programs
void bind_probe(py::module_& m);        ///< probe.cpp: palp.Probe, list_devices
void bind_stream(py::module_& m);       ///< stream.cpp: sample and gap dtypes, Probe.read
void bind_experiments(py::module_& m);  ///< experiments.cpp: indent and its settings and run
void bind_identification(py::module_& m);  ///< identification.cpp: identify, its settings and run
void bind_record(py::module_& m);       ///< record.cpp: record, the SDK recorder
void bind_analysis(py::module_& m);     ///< analysis.cpp: recordings and the offline analysis
void bind_robot(py::module_& m);        ///< robot.cpp: Robot, rig and plan files, maps
void bind_trace(py::module_& m);        ///< trace.cpp: trace, save_trace, load_trace

}  // namespace palp_python
