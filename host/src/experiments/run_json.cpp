// SPDX-License-Identifier: Apache-2.0
// result.json's "run" block (run_json.hpp).
#include "run_json.hpp"

#include <cstddef>
#include <cstdint>

#include "format/field_table.hpp"
#include "palp/protocol/messages.hpp"

namespace palp {

namespace {

using format::Field;
using format::Need;

/// The block in the file's units, the members a table can name.
struct RunBlock {
  std::string end;
  double t_device_s = 0;
  int repetitions_done = 0;
  std::size_t samples = 0;
  std::uint64_t samples_missing = 0;
  bool interrupted = false;
  double float_z_m = 0;
  std::uint32_t control_rate_Hz = 0;
};

const Field<RunBlock> kIndentationRunFields[] = {
    {"end", &RunBlock::end, 1.0, Need::written},
    {"t_device_s", &RunBlock::t_device_s},
    {"repetitions_done", &RunBlock::repetitions_done},
    {"samples", &RunBlock::samples, 1.0, Need::written},
    {"samples_missing", &RunBlock::samples_missing},
    {"interrupted", &RunBlock::interrupted},
    {"float_z_mm", &RunBlock::float_z_m, format::kMm},
};

const Field<RunBlock> kIdentificationRunFields[] = {
    {"end", &RunBlock::end, 1.0, Need::written},
    {"t_device_s", &RunBlock::t_device_s},
    {"samples", &RunBlock::samples, 1.0, Need::written},
    {"samples_missing", &RunBlock::samples_missing},
    {"interrupted", &RunBlock::interrupted},
    {"control_rate_Hz", &RunBlock::control_rate_Hz},
};

RunBlock block_of(const ProgramResult& program, bool interrupted, std::size_t samples,
                  std::uint64_t samples_missing) {
  const char* end = proto::enum_name(program.end);
  RunBlock b;
  b.end = interrupted ? "interrupted" : end ? end : "unknown";
  b.t_device_s = program.t_device_s;
  b.repetitions_done = program.repetitions_done;
  b.samples = samples;
  b.samples_missing = samples_missing;
  b.interrupted = interrupted;
  return b;
}

RunBlock read_block(const nlohmann::json& j, std::span<const Field<RunBlock>> table) {
  if (!j.is_object()) throw ConfigError("\"run\" is not an object");
  RunBlock b;
  format::read_fields(format::JsonSource(j, "run.", format::Naming::dotted_path), b, table);
  return b;
}

}  // namespace

nlohmann::json indentation_run_json(const IndentationRun& run) {
  RunBlock b = block_of(run.program, run.interrupted, run.recording.size(), run.samples_missing);
  b.float_z_m = run.float_z_m;
  nlohmann::json j = nlohmann::json::object();
  format::write_fields(j, b, kIndentationRunFields);
  return j;
}

void read_indentation_run(const nlohmann::json& run_block, IndentationRun& run) {
  const RunBlock b = read_block(run_block, kIndentationRunFields);
  run.program.t_device_s = b.t_device_s;
  run.program.repetitions_done = b.repetitions_done;
  run.samples_missing = b.samples_missing;
  run.interrupted = b.interrupted;
  run.float_z_m = b.float_z_m;
}

nlohmann::json identification_run_json(const IdentificationRun& run) {
  RunBlock b = block_of(run.program, run.interrupted, run.recording.size(), run.samples_missing);
  b.control_rate_Hz = run.control_rate_Hz;
  nlohmann::json j = nlohmann::json::object();
  format::write_fields(j, b, kIdentificationRunFields);
  return j;
}

void read_identification_run(const nlohmann::json& run_block, IdentificationRun& run) {
  const RunBlock b = read_block(run_block, kIdentificationRunFields);
  run.program.t_device_s = b.t_device_s;
  run.samples_missing = b.samples_missing;
  run.interrupted = b.interrupted;
  run.control_rate_Hz = b.control_rate_Hz;
}

}  // namespace palp
