// SPDX-License-Identifier: Apache-2.0
// The SDK recorder (palp/recorder.hpp): palp.record(probe, out, ...) streams the probe into a
// recording (run.csv + run.json), optionally while a device program runs, exactly as
// `palpctl stream` / `palpctl run` write it. The keywords are RecordSettings' fields (SI: s, Hz);
// it returns the RecordResult. The GIL is released while it records; Ctrl-C turns the recorder's
// `cancelled` callback true, the recorder stops what it started (the program: coil to 0 A) and
// writes what came, and then KeyboardInterrupt is raised (the recording is on disk).
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "palp/recorder.hpp"

namespace palp_python {

namespace {

using palp::RecordResult;
using palp::RecordSettings;

/// One of the programs a recording can run, or a ConfigError naming them.
palp::RecordedProgram program_of(const py::handle& p) {
  if (py::isinstance<palp::HoldProgram>(p)) return p.cast<palp::HoldProgram>();
  if (py::isinstance<palp::RampProgram>(p)) return p.cast<palp::RampProgram>();
  if (py::isinstance<palp::SineProgram>(p)) return p.cast<palp::SineProgram>();
  if (py::isinstance<palp::SweepProgram>(p)) return p.cast<palp::SweepProgram>();
  throw palp::ConfigError("record: program is one of HoldProgram, RampProgram, SineProgram, SweepProgram, not " +
                          py::cast<std::string>(py::type::of(p).attr("__name__")));
}

RecordResult record(palp::Probe& probe, const std::filesystem::path& out, double duration_s, double rate_Hz,
                    const py::object& program, bool zero_current, bool zero_pressure, double zero_s,
                    double reply_timeout_s, bool overwrite, const py::object& progress) {
  RecordSettings settings;
  settings.out = out;
  settings.overwrite = overwrite ? palp::Overwrite::yes : palp::Overwrite::no;
  settings.rate_Hz = rate_Hz;
  settings.duration_s = duration_s;
  if (!program.is_none()) settings.program = program_of(program);
  settings.zero_current = zero_current;
  settings.zero_pressure = zero_pressure;
  settings.zero_s = zero_s;
  settings.reply_timeout_s = reply_timeout_s;
  Interrupt interrupt;
  settings.cancelled = interrupt.callback();
  if (!progress.is_none())
    settings.progress = [&progress, &interrupt](const palp::RecordProgress& p) {
      interrupt.call(progress, p);  // a Ctrl-C inside it cancels, as poll() would
    };
  palp::Recorder recorder(std::move(settings));  // refuses an existing recording before any I/O
  RecordResult result;
  {
    py::gil_scoped_release unlocked;
    result = recorder.run(probe);
  }
  interrupt.rethrow_if_interrupted();
  return result;
}

}  // namespace

void bind_record(py::module_& m) {
  py::class_<palp::RecordProgress>(m, "RecordProgress", "record()'s progress, after every batch of samples.")
      .def_readonly("samples", &palp::RecordProgress::samples)
      .def_readonly("expected_samples", &palp::RecordProgress::expected_samples)
      .def_readonly("samples_missing", &palp::RecordProgress::samples_missing)
      .def_readonly("finished", &palp::RecordProgress::finished);

  py::class_<RecordResult>(m, "RecordResult", "What record() wrote.")
      .def_readonly("written", &RecordResult::written)
      .def_readonly("csv", &RecordResult::csv)
      .def_readonly("sidecar", &RecordResult::sidecar)
      .def_readonly("samples", &RecordResult::samples)
      .def_readonly("samples_missing", &RecordResult::samples_missing)
      .def_readonly("gaps", &RecordResult::gaps)
      .def_readonly("interrupted", &RecordResult::interrupted)
      .def_readonly("program", &RecordResult::program)
      .def_property_readonly(
          "sidecar_written",
          [](const RecordResult& r) -> py::object {
            if (!r.written) return py::none();
            return to_python(palp::sidecar_to_json(r.sidecar_written));
          },
          "The sidecar as written, csv_rows, csv_crc32 and created_utc included (the dict "
          "Recording.sidecar reads back); None when nothing was written.");

  m.def("record", &record, py::arg("probe"), py::arg("out"), py::kw_only(), py::arg("duration_s") = 0.0,
        py::arg("rate_Hz") = 1000.0, py::arg("program") = py::none(), py::arg("zero_current") = false,
        py::arg("zero_pressure") = false, py::arg("zero_s") = 0.5, py::arg("reply_timeout_s") = 2.0,
        py::arg("overwrite") = false, py::arg("progress") = py::none(),
        "Records the probe's stream into out (run or run.csv, its sidecar beside it) for duration_s "
        "of stream time, or while program runs (palp/recorder.hpp). Ctrl-C ends the recording, "
        "keeps it on disk, and raises KeyboardInterrupt.");
}

}  // namespace palp_python
