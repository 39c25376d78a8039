// SPDX-License-Identifier: Apache-2.0
// The recording options of `stream` and `run`, and their acquisition through palp::Recorder.
#include "acquire.hpp"

#include <filesystem>
#include <iostream>
#include <variant>

#include "palp/recording.hpp"

namespace palpctl {

void add_acquire_options(CLI::App& cmd, AcquireOptions& o) {
  cmd.add_option("--out", o.out, "The recording: run.csv, with its sidecar run.json beside it")
      ->capture_default_str();
  cmd.add_flag("--overwrite", o.overwrite, "Replace an existing recording of that name");
  cmd.add_option("--rate-Hz", o.rate_Hz,
                 "Stream sample rate, Hz (divides the device's control rate: 10000, 5000, 2000, "
                 "1000, ...)")
      ->check(kPositive)
      ->capture_default_str();
  cmd.add_flag("--zero-current", o.zero_current,
               "First zero the current-sense offset (device RAM only; kept in the sidecar)");
  cmd.add_flag("--zero-pressure", o.zero_pressure,
               "First zero the pressure channels, unloaded (device RAM only; kept in the sidecar)");
  cmd.add_option("--zero-s", o.zero_s, "Averaging time of each zeroing, s")
      ->check(CLI::Range(0.01, 60.0))
      ->capture_default_str();
}

int acquire(const Context& ctx, const AcquireOptions& o,
            const std::optional<palp::RecordedProgram>& program) {
  const std::string label = program ? "run " + palp::program_kind(*program) : "stream";
  // run hold's --seconds is the hold's own duration: the program ends itself
  const bool hold = program && std::holds_alternative<palp::HoldProgram>(*program);
  const double duration_s = hold ? 0.0 : o.seconds;
  if (!program && !(o.seconds > 0)) throw palp::ConfigError("stream: --seconds must be above 0");
  if (program && !(palp::expected_duration_s(*program) > 0) && !(duration_s > 0))
    throw palp::ConfigError(label + " runs until stopped with these options; give --seconds");
  // the files first: an existing recording is refused before the device does anything
  const auto csv = palp::recording_csv_path(o.out);
  for (const auto& f : {csv, palp::recording_sidecar_path(csv)})
    if (!o.overwrite && std::filesystem::exists(f))
      throw palp::ConfigError(f.string() + " already exists; choose another --out, or pass "
                              "--overwrite to replace it");

  std::optional<Progress> progress;
  palp::Recorder recorder({.out = o.out,
                           .overwrite = o.overwrite ? palp::Overwrite::yes : palp::Overwrite::no,
                           .rate_Hz = o.rate_Hz,
                           .duration_s = duration_s,
                           .program = program,
                           .zero_current = o.zero_current,
                           .zero_pressure = o.zero_pressure,
                           .zero_s = o.zero_s,
                           .reply_timeout_s = ctx.timeout_s,
                           .no_program_reason = "palpctl stream: no program ran",
                           .cancelled = [] { return interrupted(); },
                           .progress = [&](const palp::RecordProgress& p) {
                             if (!progress) progress.emplace(label, p.expected_samples, !ctx.json);
                             if (p.finished) {
                               progress->finish(p.samples);
                             } else {
                               progress->update(p.samples);
                             }
                           }});
  auto probe = ctx.connect();
  catch_interrupts();  // from here Ctrl-C stops cleanly and keeps what was recorded
  const palp::RecordResult r = recorder.run(probe);

  json summary = {{"recording", r.csv.string()},
                  {"sidecar", r.sidecar.string()},
                  {"samples", r.samples},
                  {"samples_missing", r.samples_missing},
                  {"gaps", r.gaps},
                  {"interrupted", r.interrupted}};
  if (program) summary["program"] = r.sidecar_written.program;
  if (ctx.json) {
    print_json(summary);
  } else {
    std::cout << "wrote " << r.csv.string() << " (" << r.samples << " samples, "
              << r.samples_missing << " missing) and " << r.sidecar.string() << '\n';
    if (r.program) std::cout << label << ": " << name_of(r.program->end) << '\n';
  }
  return r.interrupted ? kInterrupted : kOk;
}

}  // namespace palpctl
