// SPDX-License-Identifier: Apache-2.0
// Experiments: palp.indent(probe, settings) with IndentationSettings / IndentationParams (SI, as
// the C++ structs) and the IndentationRun it gives. run.summary() is the SDK's own JSON
// (indentation_summary_json, pressure_summary_json): the keys `palpctl indent --json` prints.
// Ctrl-C during indent(): the SDK's `cancelled` callback turns true, the SDK stops the ramp and
// leaves the coil at 0 A, then KeyboardInterrupt is raised.
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "palp/indent.hpp"
#include "palp/result.hpp"

namespace palp_python {

namespace {

using palp::IndentationRun;
using palp::IndentationSettings;
namespace an = palp::analysis;

palp::IndentationPreset preset_of(const std::string& name) {
  if (name == "1d") return palp::IndentationPreset::one_d;
  if (name == "2d") return palp::IndentationPreset::two_d;
  throw palp::ConfigError("indentation preset \"" + name + "\": one of 1d, 2d");
}

nlohmann::json run_summary(const IndentationRun& run) {
  nlohmann::json j = run.analysis ? palp::indentation_summary_json(
                                        *run.analysis, run.repetitions ? &*run.repetitions : nullptr,
                                        run.settings.analysis)
                                  : nlohmann::json{{"params", palp::indentation_params_json(run.settings.analysis)}};
  if (!run.analysis) j["analysis_reason"] = run.analysis_reason;
  if (run.pressure) {
    j["pressure"] = palp::pressure_summary_json(*run.pressure);
  } else {
    j["pressure"] = nullptr;
    j["pressure_reason"] = run.pressure_reason;
  }
  return j;
}

IndentationRun indent(palp::Probe& probe, const IndentationSettings& settings, const py::object& progress) {
  Interrupt interrupt;
  palp::IndentProgressFn on_progress;
  if (!progress.is_none())
    on_progress = [&progress, &interrupt](const palp::IndentProgress& p) { interrupt.call(progress, p); };
  IndentationRun run;
  {
    py::gil_scoped_release release;
    run = palp::indent(probe, settings, on_progress, interrupt.callback());
  }
  interrupt.rethrow_if_interrupted();
  return run;
}

}  // namespace

void bind_experiments(py::module_& m) {
  py::class_<an::IndentationParams>(m, "IndentationParams",
                                    "The indentation analysis' instrument constants and options, SI.")
      .def(py::init<>())
      .def_readwrite("force_constant_N_per_A", &an::IndentationParams::force_constant_N_per_A)
      .def_readwrite("contact_current_A", &an::IndentationParams::contact_current_A)
      .def_readwrite("spring_N_per_m", &an::IndentationParams::spring_N_per_m)
      .def_readwrite("tip_radius_m", &an::IndentationParams::tip_radius_m)
      .def_readwrite("poisson", &an::IndentationParams::poisson)
      .def_readwrite("bias_current_A", &an::IndentationParams::bias_current_A)
      .def_readwrite("window_lo_m", &an::IndentationParams::window_lo_m)
      .def_readwrite("window_hi_m", &an::IndentationParams::window_hi_m)
      .def_readwrite("local_half_width_m", &an::IndentationParams::local_half_width_m)
      .def_readwrite("tangent_depths_m", &an::IndentationParams::tangent_depths_m)
      .def_readwrite("min_points", &an::IndentationParams::min_points)
      .def("to_dict", [](const an::IndentationParams& p) { return to_python(palp::indentation_params_json(p)); },
           "The params as palpctl names them (lab units: indentation_params_json).");

  py::class_<IndentationSettings>(m, "IndentationSettings", "The indentation experiment's settings, SI.")
      .def(py::init<>())
      .def_static("preset", [](const std::string& name) { return IndentationSettings::preset(preset_of(name)); },
                  py::arg("name"), "The issue's protocols: \"1d\" or \"2d\".")
      .def_static("from_dict", [](const py::handle& d) { return palp::indentation_settings_from_json(to_json(d)); },
                  py::arg("d"), "to_dict() read back (result.json's \"parameters\").")
      .def_readwrite("start_A", &IndentationSettings::start_A)
      .def_readwrite("stop_A", &IndentationSettings::stop_A)
      .def_readwrite("step_A", &IndentationSettings::step_A)
      .def_readwrite("dwell_s", &IndentationSettings::dwell_s)
      .def_readwrite("repetitions", &IndentationSettings::repetitions)
      .def_readwrite("unload", &IndentationSettings::unload)
      .def_readwrite("displacement_limit_m", &IndentationSettings::displacement_limit_m)
      .def_readwrite("stream_rate_Hz", &IndentationSettings::stream_rate_Hz)
      .def_readwrite("zero_pressure", &IndentationSettings::zero_pressure)
      .def_readwrite("zero_pressure_s", &IndentationSettings::zero_pressure_s)
      .def_readwrite("settle_s", &IndentationSettings::settle_s)
      .def_readwrite("analysis", &IndentationSettings::analysis)
      .def("ramp_program", &IndentationSettings::ramp_program)
      .def("ramp_duration_s", &IndentationSettings::ramp_duration_s)
      .def("validate", &IndentationSettings::validate, "ConfigError naming the first bad setting.")
      .def("to_dict", [](const IndentationSettings& s) { return to_python(palp::indentation_settings_json(s)); },
           "result.json's \"parameters\" (lab units: indentation_settings_json).");

  py::class_<palp::IndentProgress>(m, "IndentProgress", "indent()'s progress, a few times a second.")
      .def_readonly("phase", &palp::IndentProgress::phase)
      .def_readonly("fraction", &palp::IndentProgress::fraction)
      .def_readonly("repetition", &palp::IndentProgress::repetition)
      .def_readonly("z_m", &palp::IndentProgress::z_m)
      .def_readonly("i_A", &palp::IndentProgress::i_A);

  py::class_<IndentationRun>(m, "IndentationRun", "What one indentation gave.")
      .def_readonly("settings", &IndentationRun::settings)
      .def_readonly("recording", &IndentationRun::recording)
      .def_readonly("device", &IndentationRun::device)
      .def_readonly("program", &IndentationRun::program)
      .def_readonly("interrupted", &IndentationRun::interrupted)
      .def_readonly("samples_missing", &IndentationRun::samples_missing)
      .def_readonly("float_z_m", &IndentationRun::float_z_m)
      .def_readonly("analysis_reason", &IndentationRun::analysis_reason)
      .def_readonly("pressure_reason", &IndentationRun::pressure_reason)
      .def_property_readonly("has_analysis", [](const IndentationRun& r) { return r.analysis.has_value(); })
      .def("summary", [](const IndentationRun& r) { return to_python(run_summary(r)); },
           "The analysed numbers in lab units with the keys of `palpctl indent --json` (the SDK's "
           "indentation_summary_json, with \"pressure\").")
      .def(
          "write_result",
          [](const IndentationRun& r, const std::filesystem::path& dir, bool overwrite) {
            return palp::write_result(dir, r, overwrite ? palp::Overwrite::yes : palp::Overwrite::no);
          },
          py::arg("dir"), py::arg("overwrite") = false, py::call_guard<py::gil_scoped_release>(),
          "Writes the result directory (result.json, indentation.csv + .json) as palpctl indent does.");

  m.def("indent", &indent, py::arg("probe"), py::arg("settings"), py::arg("progress") = py::none(),
        "Quasi-static indentation at the probe's position (palp/indent.hpp). Ctrl-C stops the ramp, "
        "leaves the coil at 0 A and raises KeyboardInterrupt.");
}

}  // namespace palp_python
