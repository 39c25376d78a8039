// SPDX-License-Identifier: Apache-2.0
// Identification (palp/identification.hpp): the frequency response in contact or in free air,
// stepped sine or multisine, and its second-order fit. run.summary() is the SDK's
// sweep_summary_json (the keys of `palpctl sweep --json`); run.frf_table() the frf.csv text.
// palp.analyze.sweep(recording) re-analyses a recording identify() wrote, without a device.
// Ctrl-C during identify(): the program stops, the coil goes to 0 A, then KeyboardInterrupt.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "palp/identification.hpp"
#include "palp/identification_result.hpp"

namespace palp_python {

namespace {

using palp::IdentificationRun;
using palp::IdentificationSettings;

palp::IdentificationPreset preset_of(const std::string& name) {
  if (name == "contact_stepped") return palp::IdentificationPreset::contact_stepped;
  if (name == "contact_multisine") return palp::IdentificationPreset::contact_multisine;
  if (name == "free_air") return palp::IdentificationPreset::free_air;
  if (name == "contact_multisine_fast") return palp::IdentificationPreset::contact_multisine_fast;
  throw palp::ConfigError(
      "identification preset \"" + name +
      "\": one of contact_stepped, contact_multisine, free_air, contact_multisine_fast");
}

nlohmann::json summary_of(const IdentificationRun& r) {
  if (r.frf && r.fit) return palp::sweep_summary_json(*r.frf, *r.fit);
  return nlohmann::json{{"analysis_reason", r.analysis_reason}};
}

IdentificationRun identify(palp::Probe& probe, const IdentificationSettings& settings, const py::object& progress) {
  Interrupt interrupt;
  palp::IdentifyProgressFn on_progress;
  if (!progress.is_none())
    on_progress = [&progress, &interrupt](const palp::IdentifyProgress& p) {
      interrupt.call(progress, p.phase, p.fraction, p.f_Hz);
    };
  IdentificationRun run;
  {
    py::gil_scoped_release unlocked;
    run = palp::identify(probe, settings, on_progress, interrupt.callback());
  }
  interrupt.rethrow_if_interrupted();
  return run;
}

/// A recording identify() wrote, analysed again: sweep_summary_json, or its analysis_reason.
py::object analyze_sweep(const palp::Recording& recording) {
  nlohmann::json j;
  {
    py::gil_scoped_release unlocked;
    IdentificationRun run = palp::identification_run_of(recording);
    palp::analyze_identification(run);
    j = summary_of(run);
  }
  return to_python(j);
}

}  // namespace

void bind_identification(py::module_& m) {
  py::class_<IdentificationSettings>(m, "IdentificationSettings", "An identification's settings, SI.")
      .def(py::init<>())
      .def_static("preset", [](const std::string& name) { return IdentificationSettings::preset(preset_of(name)); },
                  py::arg("name"),
                  "\"contact_stepped\", \"contact_multisine\", \"free_air\" or "
                  "\"contact_multisine_fast\" (<= 20 s of device time).")
      .def_static("from_dict",
                  [](const py::handle& d) { return palp::identification_settings_from_json(to_json(d)); },
                  py::arg("d"), "to_dict() read back.")
      .def_readwrite("in_contact", &IdentificationSettings::in_contact)
      .def_readwrite("bias_A", &IdentificationSettings::bias_A)
      .def_readwrite("amplitude_A", &IdentificationSettings::amplitude_A)
      .def_readwrite("f_lo_Hz", &IdentificationSettings::f_lo_Hz)
      .def_readwrite("f_hi_Hz", &IdentificationSettings::f_hi_Hz)
      .def_readwrite("step_Hz", &IdentificationSettings::step_Hz)
      .def_readwrite("fundamental_Hz", &IdentificationSettings::fundamental_Hz)
      .def_readwrite("line_step", &IdentificationSettings::line_step)
      .def_readwrite("measured_periods", &IdentificationSettings::measured_periods)
      .def_readwrite("stream_rate_Hz", &IdentificationSettings::stream_rate_Hz)
      .def_readwrite("settle_s", &IdentificationSettings::settle_s)
      .def_property_readonly("method", [](const IdentificationSettings& s) { return palp::sweep_method_name(s.method); })
      .def("validate", &IdentificationSettings::validate, "ConfigError naming the first bad setting.")
      .def("to_dict", [](const IdentificationSettings& s) { return to_python(palp::identification_settings_json(s)); },
           "The settings as the sidecar keeps them (lab units in the keys).");

  py::class_<IdentificationRun>(m, "IdentificationRun", "What one identification gave.")
      .def_readonly("settings", &IdentificationRun::settings)
      .def_readonly("recording", &IdentificationRun::recording)
      .def_readonly("program", &IdentificationRun::program)
      .def_readonly("interrupted", &IdentificationRun::interrupted)
      .def_readonly("samples_missing", &IdentificationRun::samples_missing)
      .def_readonly("analysis_reason", &IdentificationRun::analysis_reason)
      .def_property_readonly("has_analysis", [](const IdentificationRun& r) { return r.frf && r.fit; })
      .def("summary", [](const IdentificationRun& r) { return to_python(summary_of(r)); },
           "sweep_summary_json (the keys of `palpctl sweep --json`), or {analysis_reason}.")
      .def("frf_table", [](const IdentificationRun& r) -> py::object {
             if (!r.frf) return py::none();
             return py::str(palp::format_frf_table(*r.frf));
           }, "The response as frf.csv's text (f_Hz, re_m_per_N, im_m_per_N, sigma_m_per_N), or None.")
      .def(
          "write_result",
          [](const IdentificationRun& r, const std::filesystem::path& dir, bool overwrite) {
            const nlohmann::json analysis = r.frf && r.fit ? summary_of(r) : nlohmann::json();
            return palp::write_identification_result(dir, r, analysis,
                                                     overwrite ? palp::Overwrite::yes : palp::Overwrite::no);
          },
          py::arg("dir"), py::arg("overwrite") = false, "Writes the result directory (result.json, sweep.csv, frf.csv).");

  m.def("identify", &identify, py::arg("probe"), py::arg("settings"), py::arg("progress") = py::none(),
        "Identification at the probe's position (palp/identification.hpp); progress(phase, fraction, "
        "f_Hz). Ctrl-C stops the program, leaves the coil at 0 A and raises KeyboardInterrupt.");
  m.def("_analyze_sweep", &analyze_sweep, py::arg("recording"));
}

}  // namespace palp_python
