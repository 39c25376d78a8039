// SPDX-License-Identifier: Apache-2.0
// palp._palp: the SDK bound for Python (docs/python.md). The package palp re-exports it.
#include "bindings.hpp"

#include "palp/probe.hpp"

PYBIND11_MODULE(_palp, m) {
  m.doc() = "The palp SDK (C++) for Python: SI units, numpy sample arrays, palp.Error exceptions.";
  m.attr("sdk_version") = palp::sdk_version();
  palp_python::bind_errors(m);
  palp_python::bind_messages(m);
  palp_python::bind_probe(m);
  palp_python::bind_stream(m);
  palp_python::bind_experiments(m);
  palp_python::bind_identification(m);
  palp_python::bind_record(m);
  palp_python::bind_analysis(m);
  palp_python::bind_robot(m);
  palp_python::bind_trace(m);
  palp_python::bind_calibration(m);
  palp_python::bind_log(m);
}
