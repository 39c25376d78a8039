// SPDX-License-Identifier: Apache-2.0
// A device program's parameters as a sidecar's program.parameters holds them (result.hpp): one
// field table per program, written and read.
#include <cmath>
#include <string>

#include "experiment_common.hpp"
#include "format/field_table.hpp"
#include "palp/result.hpp"

namespace palp {

namespace {

using nlohmann::json;
using format::Field;

const Field<HoldProgram> kHoldFields[] = {
    {"current_A", &HoldProgram::current_A},
    {"seconds", &HoldProgram::duration_s},
};
// unload (a bool in the file) and displacement_limit_mm (counts in the message) by hand
const Field<RampProgram> kRampFields[] = {
    {"start_A", &RampProgram::start_A},
    {"stop_A", &RampProgram::stop_A},
    {"step_A", &RampProgram::step_A},
    {"dwell_s", &RampProgram::dwell_s},
    {"reps", &RampProgram::repetitions},
};
const Field<SineProgram> kSineFields[] = {
    {"offset_A", &SineProgram::offset_A},
    {"amplitude_A", &SineProgram::amplitude_A},
    {"frequency_Hz", &SineProgram::frequency_Hz},
    {"cycles", &SineProgram::cycles},
};
const Field<SweepProgram> kSweepFields[] = {
    {"offset_A", &SweepProgram::offset_A},
    {"amplitude_A", &SweepProgram::amplitude_A},
    {"start_Hz", &SweepProgram::start_Hz},
    {"stop_Hz", &SweepProgram::stop_Hz},
    {"step_Hz", &SweepProgram::step_Hz},
    {"settle_cycles", &SweepProgram::settle_cycles},
    {"settle_min_s", &SweepProgram::settle_min_s},
    {"measure_cycles", &SweepProgram::measure_cycles},
};
// phase_mode (its name) by hand
const Field<MultisineProgram> kMultisineFields[] = {
    {"offset_A", &MultisineProgram::offset_A},
    {"fundamental_Hz", &MultisineProgram::fundamental_Hz},
    {"line_first", &MultisineProgram::line_first},
    {"line_last", &MultisineProgram::line_last},
    {"line_step", &MultisineProgram::line_step},
    {"line_amplitude_A", &MultisineProgram::line_amplitude_A},
    {"phase_seed", &MultisineProgram::phase_seed},
    {"periods", &MultisineProgram::periods},
};

template <class P, std::size_t N>
json written(const P& m, const Field<P> (&table)[N]) {
  json j;
  format::write_fields(j, m, table);
  return j;
}

template <class P, std::size_t N>
format::JsonSource source(const json& j, const std::string& where, P& m, const Field<P> (&table)[N]) {
  if (!j.is_object()) throw ConfigError(where + ": the program's parameters are not an object");
  format::JsonSource src(j, where);
  format::read_fields(src, m, table);
  return src;
}

}  // namespace

proto::PhaseMode experiment::phase_mode_named(const std::string& name, const std::string& where) {
  for (const auto& v : proto::EnumInfo<proto::PhaseMode>::values)
    if (name == v.name) return static_cast<proto::PhaseMode>(v.value);
  throw ConfigError(where + ": unknown phase_mode \"" + name + "\" (random_seeded, schroeder or zero)");
}

json program_json(const HoldProgram& m) { return written(m, kHoldFields); }
json program_json(const RampProgram& m) {
  json j = written(m, kRampFields);
  j["unload"] = m.unload != 0;
  j["displacement_limit_mm"] = m.displacement_limit_counts / 1e3;
  return j;
}
json program_json(const SineProgram& m) { return written(m, kSineFields); }
json program_json(const SweepProgram& m) { return written(m, kSweepFields); }
json program_json(const MultisineProgram& m) {
  json j = written(m, kMultisineFields);
  const char* mode = proto::enum_name(m.phase_mode);
  j["phase_mode"] = mode ? mode : "?";
  return j;
}

void read_program(const json& j, const std::string& where, HoldProgram& m) { source(j, where, m, kHoldFields); }
void read_program(const json& j, const std::string& where, RampProgram& m) {
  const format::JsonSource src = source(j, where, m, kRampFields);
  m.unload = src.boolean("unload") ? 1 : 0;
  m.displacement_limit_counts =
      static_cast<std::uint32_t>(std::lround(src.number("displacement_limit_mm", {}) * 1e3));
}
void read_program(const json& j, const std::string& where, SineProgram& m) { source(j, where, m, kSineFields); }
void read_program(const json& j, const std::string& where, SweepProgram& m) { source(j, where, m, kSweepFields); }
void read_program(const json& j, const std::string& where, MultisineProgram& m) {
  const format::JsonSource src = source(j, where, m, kMultisineFields);
  m.phase_mode = experiment::phase_mode_named(src.text("phase_mode"), where);
}

}  // namespace palp
