// SPDX-License-Identifier: Apache-2.0
// The K_f calibration (palp/identification.hpp): palp.calibrate_kf(probe, settings, progress)
// runs the free-air staircase, fits K_f(stroke) and writes the table to the device (RAM, or flash
// with settings.commit). run.to_dict() is the SDK's kf_calibration_json: the keys of `palpctl
// calibrate kf --json`. Ctrl-C: the staircase stops, the coil goes to 0 A, nothing is written to
// the device, then KeyboardInterrupt is raised.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "palp/identification.hpp"
#include "palp/identification_result.hpp"

namespace palp_python {

namespace {

using palp::KfCalibrationRun;
using palp::KfCalibrationSettings;

KfCalibrationRun calibrate_kf(palp::Probe& probe,
                              const std::optional<KfCalibrationSettings>& settings,
                              const py::object& progress) {
  Interrupt interrupt;
  palp::IdentifyProgressFn on_progress;
  if (!progress.is_none())
    on_progress = [&progress, &interrupt](const palp::IdentifyProgress& p) {
      interrupt.call(progress, p.phase, p.fraction);
    };
  KfCalibrationRun run;
  {
    py::gil_scoped_release unlocked;
    run = palp::calibrate_kf(probe, settings.value_or(KfCalibrationSettings{}), on_progress,
                             interrupt.callback());
  }
  interrupt.rethrow_if_interrupted();
  return run;
}

py::object anchor_of(const KfCalibrationSettings& s) {
  if (!s.anchor) return py::none();
  return py::make_tuple(s.anchor->stroke_m, s.anchor->kf_N_per_A);
}

void set_anchor(KfCalibrationSettings& s, const std::optional<std::pair<double, double>>& a) {
  if (a)
    s.anchor = palp::analysis::KfAnchor{a->first, a->second};
  else
    s.anchor.reset();
}

}  // namespace

void bind_calibration(py::module_& m) {
  py::class_<KfCalibrationSettings>(m, "KfCalibrationSettings",
                                    "The K_f calibration's settings, SI (palp/identification.hpp).")
      .def(py::init<>())
      .def_readwrite("start_A", &KfCalibrationSettings::start_A)
      .def_readwrite("stop_A", &KfCalibrationSettings::stop_A)
      .def_readwrite("step_A", &KfCalibrationSettings::step_A)
      .def_readwrite("dwell_s", &KfCalibrationSettings::dwell_s)
      .def_readwrite("settled_fraction", &KfCalibrationSettings::settled_fraction)
      .def_readwrite("max_nodes", &KfCalibrationSettings::max_nodes)
      .def_readwrite("k_v_N_per_m", &KfCalibrationSettings::k_v_N_per_m)
      .def_readwrite("stream_rate_Hz", &KfCalibrationSettings::stream_rate_Hz)
      .def_readwrite("write", &KfCalibrationSettings::write)
      .def_readwrite("commit", &KfCalibrationSettings::commit)
      .def_property("anchor", &anchor_of, &set_anchor,
                    "(stroke_m, kf_N_per_A) the fit is anchored at (default the paper's (0.024, "
                    "2.918)), or None to fit without one.")
      .def("validate", &KfCalibrationSettings::validate,
           "ConfigError naming the first bad setting.");

  py::class_<KfCalibrationRun>(m, "KfCalibrationRun", "What one K_f calibration gave.")
      .def_readonly("settings", &KfCalibrationRun::settings)
      .def_readonly("recording", &KfCalibrationRun::recording)
      .def_readonly("written", &KfCalibrationRun::written)
      .def_readonly("committed", &KfCalibrationRun::committed)
      .def_readonly("interrupted", &KfCalibrationRun::interrupted)
      .def_property_readonly("node_stroke_m",
                             [](const KfCalibrationRun& r) { return r.calibration.node_stroke_m; })
      .def_property_readonly("kf_N_per_A",
                             [](const KfCalibrationRun& r) { return r.calibration.kf_N_per_A; })
      .def_property_readonly("warning",
                             [](const KfCalibrationRun& r) { return r.calibration.warning; })
      .def(
          "to_dict",
          [](const KfCalibrationRun& r) { return to_python(palp::kf_calibration_json(r)); },
          "The result with the keys of `palpctl calibrate kf --json` (kf_calibration_json).");

  m.def("calibrate_kf", &calibrate_kf, py::arg("probe"), py::arg("settings") = std::nullopt,
        py::arg("progress") = py::none(),
        "K_f along the stroke in free air (probe clear of everything), written to the device's "
        "calibration table (palp/identification.hpp); progress(phase, fraction). Ctrl-C stops the "
        "staircase, leaves the coil at 0 A, writes nothing and raises KeyboardInterrupt.");
}

}  // namespace palp_python
