// SPDX-License-Identifier: Apache-2.0
// Recordings and the analysis without a device. A recording's columns keep the file's names and
// lab units (t_s, i_A, z_mm, sample_index, i_cmd_A, p1_Pa..p6_Pa, status, rep: docs/
// recording-format.md), as numpy arrays; palp.analyze (analyze.py) builds on these.
#include <set>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "palp/indent.hpp"
#include "palp/pressure_analysis.hpp"
#include "palp/recording.hpp"
#include "palp/result.hpp"

namespace palp_python {

namespace {

namespace an = palp::analysis;

template <class T>
py::array_t<T> array_of(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::dict columns_of(const palp::Recording& r) {
  py::dict d;
  if (r.sample_index) d["sample_index"] = array_of(*r.sample_index);
  d["t_s"] = array_of(r.t_s);
  if (r.i_cmd_A) d["i_cmd_A"] = array_of(*r.i_cmd_A);
  d["i_A"] = array_of(r.i_A);
  d["z_mm"] = array_of(r.z_mm);
  for (std::size_t k = 0; k < 6; ++k)
    if (r.p_Pa[k]) d[py::str("p" + std::to_string(k + 1) + "_Pa")] = array_of(*r.p_Pa[k]);
  if (r.status) d["status"] = array_of(*r.status);
  d["rep"] = array_of(r.rep);
  return d;
}

template <class T>
std::vector<T> column(const py::dict& d, const char* name, std::size_t n) {
  const auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(d[name]);
  if (!a || a.ndim() != 1)
    throw palp::ConfigError(std::string("column ") + name + ": expected a 1-D array of numbers");
  if (n != SIZE_MAX && static_cast<std::size_t>(a.size()) != n)
    throw palp::ConfigError(std::string("column ") + name + " has " + std::to_string(a.size()) +
                            " values, t_s has " + std::to_string(n));
  return std::vector<T>(a.data(), a.data() + a.size());
}

/// A recording from columns named as in a recording file (t_s, i_A, z_mm required; rep from the
/// current's minima when absent, as the reader does).
palp::Recording recording_of(const py::dict& d) {
  for (const char* required : {"t_s", "i_A", "z_mm"})
    if (!d.contains(required))
      throw palp::ConfigError(std::string("a recording needs the columns t_s, i_A, z_mm; ") + required + " is missing");
  std::set<std::string> known = {"sample_index", "t_s", "i_cmd_A", "i_A", "z_mm", "status", "rep"};
  for (int k = 1; k <= 6; ++k) known.insert("p" + std::to_string(k) + "_Pa");
  for (auto item : d)
    if (!known.count(py::cast<std::string>(item.first)))
      throw palp::ConfigError("unknown recording column \"" + py::cast<std::string>(item.first) + "\"");
  palp::Recording r;
  r.t_s = column<double>(d, "t_s", SIZE_MAX);
  const std::size_t n = r.t_s.size();
  r.i_A = column<double>(d, "i_A", n);
  r.z_mm = column<double>(d, "z_mm", n);
  r.sample_index = d.contains("sample_index") ? std::optional(column<std::uint64_t>(d, "sample_index", n)) : std::nullopt;
  r.i_cmd_A = d.contains("i_cmd_A") ? std::optional(column<double>(d, "i_cmd_A", n)) : std::nullopt;
  r.status = d.contains("status") ? std::optional(column<std::uint16_t>(d, "status", n)) : std::nullopt;
  for (std::size_t k = 0; k < 6; ++k) {
    const std::string name = "p" + std::to_string(k + 1) + "_Pa";
    r.p_Pa[k] = d.contains(name.c_str()) ? std::optional(column<double>(d, name.c_str(), n)) : std::nullopt;
  }
  if (d.contains("rep")) {
    r.rep = column<int>(d, "rep", n);
  } else {
    r.rep = palp::split_repetitions_at_current_minima(r.i_A);
    r.rep_source = palp::RepSource::split_at_current_minima;
  }
  return r;
}

/// What `palpctl analyze indentation --json` prints for a recording (without its input and
/// kf_table keys in "params"): the SDK's indentation_summary_json of the pooled and per-repetition
/// analyses.
py::object analyze_indentation(const palp::Recording& r, const an::IndentationParams& p) {
  nlohmann::json j;
  {
    py::gil_scoped_release release;
    const an::Curve curve = palp::curve_of(r);
    const an::IndentationResult result = an::analyze_indentation(curve, p);
    const an::RepetitionSummary reps = an::analyze_repetitions(curve, p);
    j = palp::indentation_summary_json(result, &reps, p);
  }
  return to_python(j);
}

/// What `palpctl analyze pressure --json` prints for a recording (without its "force" text and
/// its input and kf_table keys in "params"): the SDK's pressure_summary_json of
/// pressure_analysis_of, the same analysis palp.indent's run.summary()["pressure"] holds.
py::object analyze_pressure(const palp::Recording& r, const an::IndentationParams& p) {
  nlohmann::json j;
  {
    py::gil_scoped_release release;
    j = palp::pressure_summary_json(palp::pressure_analysis_of(r, p));
    j["params"] = palp::indentation_params_json(p);
  }
  return to_python(j);
}

}  // namespace

void bind_analysis(py::module_& m) {
  py::class_<palp::Recording>(m, "Recording", "A recording: its columns (lab units, the file's names) and sidecar.")
      .def(py::init(&recording_of), py::arg("columns"),
           "From a dict of columns named as in a recording file (t_s, i_A, z_mm required).")
      .def_property_readonly("columns", &columns_of, "The columns as numpy arrays, by their file names.")
      .def_property_readonly("sidecar",
                             [](const palp::Recording& r) -> py::object {
                               if (!r.sidecar) return py::none();
                               return to_python(palp::sidecar_to_json(*r.sidecar));
                             })
      .def_readonly("ignored_columns", &palp::Recording::ignored_columns)
      .def("__len__", &palp::Recording::size);
  m.def("read_recording", [](const std::filesystem::path& csv) { return palp::read_recording(csv); },
        py::arg("csv"), py::call_guard<py::gil_scoped_release>(),
        "Reads run.csv (and run.json beside it); RecordingError naming the file and line.");
  m.def(
      "write_recording",
      [](const std::filesystem::path& csv, const palp::Recording& r, bool overwrite) {
        palp::write_recording(csv, r, overwrite ? palp::Overwrite::yes : palp::Overwrite::no);
      },
      py::arg("csv"), py::arg("recording"), py::arg("overwrite") = false, py::call_guard<py::gil_scoped_release>(),
      "Writes a recording (CSV + sidecar), atomically.");
  m.def("_analyze_indentation", &analyze_indentation, py::arg("recording"), py::arg("params"));
  m.def("_analyze_pressure", &analyze_pressure, py::arg("recording"), py::arg("params"));
}

}  // namespace palp_python
