// The acquisition of `stream` and `run`: zeroing (RAM only), stream, program, recording.
#include "acquire.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <iostream>
#include <limits>
#include <variant>
#include <vector>

#include "palp/result.hpp"
#include "palp/recording.hpp"
#include "ramp_reps.hpp"

namespace palpctl {

namespace {

using std::chrono::milliseconds;

milliseconds ms_from_s(double s) { return milliseconds(static_cast<long long>(std::ceil(s * 1e3))); }

palp::RecordingRow row_of(const palp::Sample& s, int rep) {
  return {.sample_index = s.index,
          .t_s = s.t_device_s,
          .i_cmd_A = s.i_cmd_A,
          .i_A = s.i_A,
          .z_mm = mm_from_counts(s.encoder_counts),
          .p_Pa = s.p_Pa,
          .status = s.status,
          .rep = rep};
}

}  // namespace

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
            const std::optional<ProgramSpec>& program) {
  const std::string label = program ? "run " + program->name : "stream";
  const double stop_after_s = program ? program->stop_after_s : o.seconds;
  if (!program && !(o.seconds > 0)) throw palp::ConfigError("stream: --seconds must be above 0");
  if (program && !(program->expected_s > 0) && !(stop_after_s > 0))
    throw palp::ConfigError(label + " runs until stopped with these options; give --seconds");

  // the file first: an existing recording is refused before the device does anything
  const auto csv = palp::recording_csv_path(o.out);
  for (const auto& f : {csv, palp::recording_sidecar_path(csv)})
    if (!o.overwrite && std::filesystem::exists(f))
      throw palp::ConfigError(f.string() + " already exists; choose another --out, or pass "
                              "--overwrite to replace it");
  palp::RecordingWriter writer(
      o.out, {.overwrite = o.overwrite ? palp::Overwrite::yes : palp::Overwrite::no});
  auto probe = ctx.connect();
  if (o.zero_current) probe.zero_current_offset(o.zero_s);
  if (o.zero_pressure) probe.zero_pressure(o.zero_s);
  const auto stream = probe.configure_stream({.rate_Hz = o.rate_Hz});
  palp::Sidecar side = palp::setup_sidecar(probe);
  side.device["params"] = to_json(probe.params());
  if (program) {
    side.program = {{"kind", program->name}, {"parameters", program->params}};
  } else {
    side.extra["program_reason"] = "palpctl stream: no program ran";
  }

  double expected_s = program ? program->expected_s : o.seconds;
  if (stop_after_s > 0 && (expected_s <= 0 || stop_after_s < expected_s)) expected_s = stop_after_s;
  const auto expected = static_cast<std::uint64_t>(std::llround(expected_s * stream.rate_Hz));
  const std::uint64_t stop_index = stop_after_s > 0
                                       ? static_cast<std::uint64_t>(std::llround(stop_after_s * stream.rate_Hz))
                                       : std::numeric_limits<std::uint64_t>::max();
  Progress progress(label, expected, !ctx.json);
  std::optional<RampReps> reps;
  if (program && program->ramp) reps.emplace(*program->ramp);

  std::uint64_t samples = 0, missing = 0;
  json gaps = json::array();
  bool stopping = false, user_stop = false, past_end = false;
  auto consume = [&](const std::vector<palp::StreamItem>& items) {
    for (const auto& item : items) {
      if (const auto* g = std::get_if<palp::Gap>(&item)) {
        missing += g->count;
        gaps.push_back({{"first_index", g->first_index},
                        {"count", g->count},
                        {"source", palp::gap_source_name(g->source)},
                        {"t_device_s", g->t_device_s}});
        continue;
      }
      const auto& s = std::get<palp::Sample>(item);
      if (!program && s.index >= stop_index) {  // a stream keeps exactly --seconds of samples
        past_end = true;
        continue;
      }
      writer.append(row_of(s, reps ? (*reps)(s) : 0));
      ++samples;
      if (s.index + 1 >= stop_index) past_end = true;
    }
  };

  catch_interrupts();  // from here Ctrl-C stops cleanly and keeps what was recorded
  if (program) program->load(probe);
  probe.start_stream();
  std::future<palp::ProgramResult> done;
  if (program) {
    probe.start();
    const double wait_s = 2 * expected_s + 30 + ctx.timeout_s;
    done = std::async(std::launch::async, [&probe, wait_s] { return probe.wait(ms_from_s(wait_s)); });
  }

  std::exception_ptr error;
  std::optional<palp::ProgramResult> result;
  std::vector<palp::StreamItem> items;
  auto last_item = std::chrono::steady_clock::now();
  const auto silence_limit = std::chrono::duration<double>(ctx.timeout_s + 5);
  try {
    for (;;) {
      items.clear();
      if (auto it = probe.next(milliseconds(50))) {
        items.push_back(*it);
        probe.drain(items);
        last_item = std::chrono::steady_clock::now();
      } else if (std::chrono::steady_clock::now() - last_item > silence_limit) {
        throw palp::TimeoutError("stream samples from " + probe.uri(), silence_limit.count(),
                                 probe.health());
      }
      consume(items);
      progress.update(samples);
      if (interrupted() && !user_stop) {
        user_stop = true;
        if (!program) break;
      }
      if (!program && past_end) break;
      if (program && !stopping && (user_stop || past_end)) {
        stopping = true;
        probe.stop();
      }
      if (program && done.wait_for(milliseconds(0)) == std::future_status::ready) {
        result = done.get();
        break;
      }
    }
  } catch (...) {
    error = std::current_exception();
  }
  // leave the device quiet, keep what is still queued, and write the recording
  try {
    if (program && done.valid()) {
      probe.stop();
      done.wait();
    }
    probe.stop_stream();
    while (auto it = probe.next(milliseconds(100))) consume({*it});
    side.extra["health"] = to_json(probe.health());
    if (program) side.program["result"] = result ? to_json(*result) : json(nullptr);
    if (program && !result) side.program["fault"] = to_json(probe.fault());
  } catch (...) {
    if (!error) error = std::current_exception();
  }
  progress.finish(samples);
  side.extra["gaps"] = gaps;
  side.extra["samples_missing"] = missing;
  side.extra["interrupted"] = user_stop;
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      side.extra["error"] = e.what();
    }
  }
  if (writer.rows() > 0) writer.finish(side);
  if (error) std::rethrow_exception(error);

  json summary = {{"recording", writer.csv_path().string()},
                  {"sidecar", writer.sidecar_path().string()},
                  {"samples", samples},
                  {"samples_missing", missing},
                  {"gaps", gaps.size()},
                  {"interrupted", user_stop}};
  if (program) summary["program"] = side.program;
  if (ctx.json) {
    print_json(summary);
  } else {
    std::cout << "wrote " << writer.csv_path().string() << " (" << samples << " samples, "
              << missing << " missing) and " << writer.sidecar_path().string() << '\n';
    if (result) std::cout << label << ": " << name_of(result->end) << '\n';
  }
  return user_stop ? kInterrupted : kOk;
}

}  // namespace palpctl
