// SPDX-License-Identifier: Apache-2.0
// Result directories (result.hpp): written into a hidden sibling directory, flushed, renamed
// into place; read back with errors that name the file.
#include <fstream>
#include <sstream>

#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "palp/result.hpp"
#include "result_dir.hpp"
#include "run_json.hpp"

namespace palp {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kIndentationStem = "indentation";

/// A required key of result.json, or a RecordingError naming it.
const json& need(const json& j, const std::string& key, const std::string& file,
                 const std::string& where = "") {
  if (!j.is_object() || !j.contains(key))
    throw RecordingError(file, 0, "missing key \"" + where + key + "\"");
  return j.at(key);
}

}  // namespace

fs::path write_result(const fs::path& dir_in, const IndentationRun& run, Overwrite overwrite) {
  if (run.recording.size() == 0)
    throw ConfigError("write_result: the run has no samples of the ramp; nothing to write");
  const fs::path dir = prepare_result_directory(dir_in, overwrite, "write_result");

  nlohmann::ordered_json summary = result_head("indentation");
  summary["device"] = run.recording.sidecar ? run.recording.sidecar->device : device_json(run.device);
  summary["firmware_version"] = run.device.firmware_version;
  summary["parameters"] = indentation_settings_json(run.settings);
  summary["recordings"] = json::array({std::string(kIndentationStem) + ".csv"});
  summary["run"] = indentation_run_json(run);
  if (run.analysis) {
    summary["analysis"] = indentation_summary_json(
        *run.analysis, run.repetitions ? &*run.repetitions : nullptr, run.settings.analysis);
  } else {
    summary["analysis"] = nullptr;
    summary["analysis_reason"] = run.analysis_reason.empty() ? "not analysed" : run.analysis_reason;
  }
  if (run.pressure) {
    summary["pressure"] = pressure_summary_json(*run.pressure);
  } else {
    summary["pressure"] = nullptr;
    summary["pressure_reason"] = run.pressure_reason.empty() ? "not analysed" : run.pressure_reason;
  }

  write_result_directory(dir, overwrite, [&](const fs::path& tmp) {
    write_recording(tmp / kIndentationStem, run.recording);
    write_text_file(tmp / kResultFile, summary.dump(2) + "\n");
  });
  return dir;
}

LoadedResult load_result(const fs::path& dir) {
  LoadedResult r;
  r.dir = dir;
  const fs::path file = dir / kResultFile;
  const std::string name = file.string();
  if (!fs::is_directory(dir)) throw RecordingError(name, 0, "no such result directory");
  if (!fs::exists(file))
    throw RecordingError(name, 0, "no result.json: not a result directory (or unreadable)");
  const std::string text = format::read_bounded_or(
      file, format::kMaxJsonFileBytes,
      [&](const std::string& problem) -> void { throw RecordingError(name, 0, problem); });
  try {
    r.summary = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    // "[json.exception.parse_error.101] parse error at line 3, column 5: ..." names the place
    const std::string what = e.what();
    const auto at = what.find("parse error");
    throw RecordingError(name, 0, "invalid JSON: " + format::escaped(at == std::string::npos
                                                                        ? what
                                                                        : what.substr(at),
                                                                    4 * format::kQuoteChars));
  }
  if (!r.summary.is_object()) throw RecordingError(name, 0, "not a JSON object");
  const json& schema = need(r.summary, "schema", name);
  if (!schema.is_string() || schema.get<std::string>() != kResultSchema)
    throw RecordingError(name, 0, "schema is " + format::escaped(schema.dump()) + ", expected \"" +
                                      std::string(kResultSchema) + "\"");
  const json& experiment = need(r.summary, "experiment", name);
  if (!experiment.is_string()) throw RecordingError(name, 0, "\"experiment\" is not a string");
  r.experiment = experiment.get<std::string>();
  const json& recordings = need(r.summary, "recordings", name);
  if (!recordings.is_array()) throw RecordingError(name, 0, "\"recordings\" is not an array");
  for (const json& f : recordings) {
    if (!f.is_string() || f.get<std::string>().empty() ||
        fs::path(f.get<std::string>()).has_parent_path())
      throw RecordingError(name, 0, "\"recordings\" holds " + format::escaped(f.dump()) +
                                        ", not a file name inside the result directory");
    const fs::path csv = dir / f.get<std::string>();
    if (!fs::exists(csv)) throw RecordingError(csv.string(), 0, "listed in result.json but missing");
    r.recordings.emplace_back(f.get<std::string>(), read_recording(csv));
  }
  return r;
}

IndentationRun indentation_run_of(const LoadedResult& result) {
  const std::string name = (result.dir / kResultFile).string();
  if (result.experiment != "indentation")
    throw RecordingError(name, 0, "experiment is " + format::quoted(result.experiment) + ", not an indentation");
  if (result.recordings.empty()) throw RecordingError(name, 0, "lists no recording");
  IndentationRun run;
  try {
    run.settings = indentation_settings_from_json(need(result.summary, "parameters", name), "parameters.");
  } catch (const ConfigError& e) {
    throw RecordingError(name, 0, e.what());
  }
  run.recording = result.recordings.front().second;
  try {
    read_indentation_run(need(result.summary, "run", name), run);
  } catch (const ConfigError& e) {
    throw RecordingError(name, 0, e.what());
  }
  if (const json& d = need(result.summary, "device", name); d.is_object()) {
    try {
      run.device = device_info_from_json(d, "\"device\"");
    } catch (const ConfigError& e) {
      throw RecordingError(name, 0, e.what());
    }
  }
  analyze_run(run);
  return run;
}

}  // namespace palp
