// SPDX-License-Identifier: Apache-2.0
// Dynamic identification (identification.hpp): float the coil, hold the bias, run the stepped
// sine or the multisine while recording, analyse; and the re-analysis of a loaded recording.
#include <algorithm>
#include <cmath>
#include <string>

#include "experiment_common.hpp"
#include "format/field_table.hpp"
#include "palp/error.hpp"
#include "palp/identification.hpp"
#include "palp/result.hpp"

namespace palp {

namespace {


constexpr double kSameCurrent_A = 1e-3;      // a bias this close to I_c needs no second hold

/// Floats the coil at I_c with a contact watch (as indent() does), then holds the bias with a
/// second watch that fires on the first micrometre the bias moves the coil: a fired watch keeps
/// its current on until the next program starts, so the bias stays on with no gap.
void float_and_hold_bias(Probe& probe, const IdentificationSettings& s,
                         const std::function<void(const char*)>& phase,
                         const std::function<bool()>& cancelled) {
  phase("floating the coil");
  std::optional<ContactEvent> event =
      experiment::float_coil(probe, s.contact_current_A, "is the tip pressed against the specimen?");
  if (std::fabs(s.bias_A - s.contact_current_A) > kSameCurrent_A) {
    ContactWatchProgram b;
    b.hold_current_A = static_cast<float>(s.bias_A);
    b.threshold_counts = 1;
    b.timeout_s = 5.0f;
    probe.load(b);
    probe.start();
    event = probe.wait_contact(10s);
    if (!event)
      throw TimeoutError("the coil to move on the step from I_c to the bias " +
                             std::to_string(s.bias_A) + " A",
                         10.0, std::nullopt);
  }
  phase("settling");
  experiment::wait_device_time(probe, event->t_device_s + s.settle_s, cancelled);
}

// Reading the sidecar's objects: every missing or mistyped key is a ConfigError naming it.
struct Reader {
  const nlohmann::json& j;
  std::string where;
  const nlohmann::json& at(const char* key) const {
    if (!j.is_object() || !j.contains(key))
      throw ConfigError(where + ": no \"" + key + "\" (the recording cannot be re-analysed)");
    return j[key];
  }
  double num(const char* key) const {
    const auto& v = at(key);
    if (!v.is_number()) throw ConfigError(where + ": \"" + key + "\" is not a number");
    return v.get<double>();
  }
  template <class T>
  T integer(const char* key) const {
    const auto& v = at(key);
    if (!v.is_number_integer() && !v.is_number_unsigned())
      throw ConfigError(where + ": \"" + key + "\" is not a whole number");
    return v.get<T>();
  }
  // a field table's Source (format/field_table.hpp; every key required, no ranges)
  bool has(const char* key) const { return j.is_object() && j.contains(key) && !j[key].is_null(); }
  double number(const char* key, const format::Range&) const { return num(key); }
  long long integer(const char* key, const format::Range&) const { return integer<long long>(key); }
  std::string text(const char* key) const { return str(key); }
  bool boolean(const char* key) const {
    const auto& v = at(key);
    if (!v.is_boolean()) throw ConfigError(where + ": \"" + key + "\" is not true or false");
    return v.get<bool>();
  }
  std::string str(const char* key) const {
    const auto& v = at(key);
    if (!v.is_string()) throw ConfigError(where + ": \"" + key + "\" is not a string");
    return v.get<std::string>();
  }
};

using format::Field;

// the settings as the sidecar's extra.identification keeps them; method, phase_mode and the
// K_f table by hand
const Field<IdentificationSettings> kSettingsFields[] = {
    {"in_contact", &IdentificationSettings::in_contact},
    {"bias_A", &IdentificationSettings::bias_A},
    {"amplitude_A", &IdentificationSettings::amplitude_A},
    {"f_lo_Hz", &IdentificationSettings::f_lo_Hz},
    {"f_hi_Hz", &IdentificationSettings::f_hi_Hz},
    {"step_Hz", &IdentificationSettings::step_Hz},
    {"settle_cycles", &IdentificationSettings::settle_cycles},
    {"settle_min_s", &IdentificationSettings::settle_min_s},
    {"measure_cycles", &IdentificationSettings::measure_cycles},
    {"fundamental_Hz", &IdentificationSettings::fundamental_Hz},
    {"line_step", &IdentificationSettings::line_step},
    {"discard_periods", &IdentificationSettings::discard_periods},
    {"measured_periods", &IdentificationSettings::measured_periods},
    {"phase_seed", &IdentificationSettings::phase_seed},
    {"stream_rate_Hz", &IdentificationSettings::stream_rate_Hz},
    {"settle_s", &IdentificationSettings::settle_s},
    {"contact_current_A", &IdentificationSettings::contact_current_A},
    {"max_excursion_mm", &IdentificationSettings::max_excursion_m, format::kMm},
};
const Field<analysis::FrfOptions> kFrfFields[] = {
    {"kf_N_per_A", &analysis::FrfOptions::force_constant_N_per_A},
    {"kf_table_stroke_origin_z_mm", &analysis::FrfOptions::stroke_origin_z_m, format::kMm},
    {"distortion_limit", &analysis::FrfOptions::distortion_limit},
};
const Field<analysis::InstrumentDynamics> kInstrumentFields[] = {
    {"m_v_kg", &analysis::InstrumentDynamics::m_v_kg},
    {"b_v_N_s_per_m", &analysis::InstrumentDynamics::b_v_N_s_per_m},
    {"k_v_N_per_mm", &analysis::InstrumentDynamics::k_v_N_per_m, format::kNPerMm},
};
const Field<analysis::SecondOrderOptions> kFitFields[] = {
    {"sk_iterations", &analysis::SecondOrderOptions::sk_iterations},
    {"max_lm_iterations", &analysis::SecondOrderOptions::max_lm_iterations},
    {"adequate_cost", &analysis::SecondOrderOptions::adequate_cost},
};

}  // namespace

nlohmann::json identification_settings_json(const IdentificationSettings& s) {
  nlohmann::json table = nlohmann::json::array();
  for (std::size_t k = 0; k < s.frf.kf_table_stroke_m.size() && k < s.frf.kf_table_N_per_A.size(); ++k)
    table.push_back({{"position_mm", s.frf.kf_table_stroke_m[k] * format::kMm},
                     {"kf_N_per_A", s.frf.kf_table_N_per_A[k]}});
  nlohmann::json j = {{"method", sweep_method_name(s.method)},
                      {"phase_mode", proto::enum_name(s.phase_mode) ? proto::enum_name(s.phase_mode) : "?"},
                      {"kf_table", table}};
  format::write_fields(j, s, kSettingsFields);
  format::write_fields(j, s.frf, kFrfFields);
  format::write_fields(j["instrument"], s.instrument, kInstrumentFields);
  format::write_fields(j["fit"], s.fit, kFitFields);
  return j;
}

IdentificationSettings identification_settings_from_json(const nlohmann::json& j) {
  const Reader r{j, "the identification settings"};
  IdentificationSettings s;
  const std::string method = r.str("method");
  if (method != "stepped" && method != "multisine")
    throw ConfigError("the identification settings: method \"" + method +
                      "\" is neither stepped nor multisine");
  s.method = method == "stepped" ? SweepMethod::stepped : SweepMethod::multisine;
  format::read_fields(r, s, kSettingsFields);
  s.phase_mode = experiment::phase_mode_named(r.str("phase_mode"), r.where);
  format::read_fields(r, s.frf, kFrfFields);
  const auto& table = r.at("kf_table");
  if (!table.is_array()) throw ConfigError("the identification settings: \"kf_table\" is not an array");
  for (const auto& row : table) {
    const Reader t{row, "the identification settings' kf_table row"};
    s.frf.kf_table_stroke_m.push_back(format::from_file(t.num("position_mm"), format::kMm));
    s.frf.kf_table_N_per_A.push_back(t.num("kf_N_per_A"));
  }
  s.frf.multisine_discard_periods = s.discard_periods;
  format::read_fields(Reader{r.at("instrument"), "the identification settings' instrument"}, s.instrument,
                      kInstrumentFields);
  format::read_fields(Reader{r.at("fit"), "the identification settings' fit"}, s.fit, kFitFields);
  return s;
}

namespace {
IdentificationRun identify_unguarded(Probe& probe, const IdentificationSettings& settings,
                                     const IdentifyProgressFn& progress, const std::function<bool()>& cancelled) {
  IdentificationRun run;
  run.settings = settings;
  run.settings.frf.multisine_discard_periods = settings.discard_periods;
  run.device = probe.info();
  run.control_rate_Hz = static_cast<std::uint32_t>(std::lround(run.device.control_rate_Hz));
  const std::uint32_t rate = run.control_rate_Hz;
  settings.check_excitation(rate);  // before the device does anything
  const bool stepped = settings.method == SweepMethod::stepped;
  if (stepped) {
    run.sweep = settings.sweep_program();
  } else {
    run.multisine = settings.multisine_program(rate);
  }
  const double duration_s = settings.device_time_s(rate);
  auto report = [&](const char* phase, double fraction, double f_Hz) {
    if (!progress) return;
    progress(IdentifyProgress{phase, std::clamp(fraction, 0.0, 1.0), f_Hz});
  };

  experiment::release_coil(probe, settings.settle_s, cancelled, [&] { report("releasing the coil", 0, 0); });
  probe.configure_stream({.rate_Hz = settings.stream_rate_Hz});

  const char* program_phase = stepped ? "stepped sine" : "multisine";
  experiment::ProgramRecording rec;
  try {
    float_and_hold_bias(probe, settings, [&](const char* p) { report(p, 0, 0); }, cancelled);
  } catch (...) {
    probe.stop();  // the coil back to 0 A
    throw;
  }
  if (cancelled && cancelled()) {
    probe.stop();
    rec.interrupted = true;
  } else {
    rec = experiment::record_program(
        probe,
        [&] {
          if (stepped) {
            probe.load(run.sweep);
          } else {
            probe.load(run.multisine);
          }
          probe.start();
        },
        duration_s,
        [&](double elapsed_s, const Sample&) {
          double f = 0;
          if (stepped) {
            const proto::ProgramStatus ps = probe.program_status();
            f = run.sweep.start_Hz + static_cast<double>(ps.step) * run.sweep.step_Hz;
          }
          report(program_phase, elapsed_s / duration_s, f);
        },
        cancelled);
  }
  report(program_phase, 1.0, 0);
  run.program = rec.program;
  run.interrupted = rec.interrupted;
  run.samples_missing = rec.samples_missing;
  run.recording = std::move(rec.recording);

  Sidecar side = experiment::base_sidecar(probe, "identification", rec);
  side.program = {{"kind", stepped ? "sweep" : "multisine"},
                  {"parameters", stepped ? program_json(run.sweep) : program_json(run.multisine)},
                  {"result",
                   {{"end", proto::enum_name(run.program.end) ? proto::enum_name(run.program.end) : "?"},
                    {"t_device_s", run.program.t_device_s},
                    {"repetitions_done", run.program.repetitions_done}}}};
  side.extra["identification"] = identification_settings_json(run.settings);
  side.extra["control_rate_Hz"] = rate;
  side.extra["device_time_s"] = duration_s;
  run.recording.sidecar = side;

  report("analysing", 1.0, 0);
  analyze_identification(run);
  return run;
}
}  // namespace

IdentificationRun identify(Probe& probe, const IdentificationSettings& settings,
                           const IdentifyProgressFn& progress, const std::function<bool()>& cancelled) {
  settings.validate();
  return experiment::or_make_safe(probe, [&] { return identify_unguarded(probe, settings, progress, cancelled); });
}

void analyze_identification(IdentificationRun& run) {
  run.frf.reset();
  run.fit.reset();
  run.analysis_reason.clear();
  if (run.recording.size() == 0) {
    run.analysis_reason = "the recording has no samples of the program";
    return;
  }
  analysis::FrfOptions options = run.settings.frf;
  options.multisine_discard_periods = run.settings.discard_periods;
  try {
    run.frf = run.settings.method == SweepMethod::stepped
                  ? analysis::stepped_sine_frf(run.recording, run.sweep, run.control_rate_Hz, options)
                  : analysis::multisine_frf(run.recording, run.multisine, run.control_rate_Hz, options);
  } catch (const DataError& e) {  // a bad setting is no data problem: it propagates
    run.analysis_reason = std::string("no frequency response: ") + e.what();
    return;
  }
  try {
    run.fit = analysis::fit_second_order(run.frf->lines, run.settings.fit);
  } catch (const DataError& e) {
    run.analysis_reason = std::string("no second-order fit: ") + e.what();
  }
}

IdentificationRun identification_run_of(const Recording& recording) {
  if (!recording.sidecar)
    throw ConfigError("the recording has no sidecar: its identification settings and program "
                      "are unknown (give them as options)");
  const Sidecar& side = *recording.sidecar;
  const Reader extra{side.extra, "the recording's sidecar"};
  IdentificationRun run;
  if (!side.extra.contains("identification"))
    throw ConfigError("the recording's sidecar has no identification settings "
                      "(extra.identification): it was not written by identify()");
  run.settings = identification_settings_from_json(side.extra["identification"]);
  run.control_rate_Hz = extra.integer<std::uint32_t>("control_rate_Hz");
  const Reader program{side.program, "the recording's sidecar program"};
  const std::string kind = program.str("kind");
  const bool stepped = run.settings.method == SweepMethod::stepped;
  if (kind != (stepped ? "sweep" : "multisine"))
    throw ConfigError("the recording's sidecar program is a \"" + kind + "\", the settings' method " +
                      sweep_method_name(run.settings.method) + " needs a " +
                      (stepped ? "sweep" : "multisine"));
  const std::string where = "the recording's sidecar program parameters";
  if (stepped) {
    read_program(program.at("parameters"), where, run.sweep);
  } else {
    read_program(program.at("parameters"), where, run.multisine);
  }
  if (side.program.contains("result") && side.program["result"].is_object()) {
    const auto& res = side.program["result"];
    if (res.contains("t_device_s") && res["t_device_s"].is_number())
      run.program.t_device_s = res["t_device_s"].get<double>();
    if (res.contains("repetitions_done") && res["repetitions_done"].is_number_integer())
      run.program.repetitions_done = res["repetitions_done"].get<int>();
  }
  if (side.extra.contains("interrupted") && side.extra["interrupted"].is_boolean())
    run.interrupted = side.extra["interrupted"].get<bool>();
  if (side.extra.contains("samples_missing") && side.extra["samples_missing"].is_number_unsigned())
    run.samples_missing = side.extra["samples_missing"].get<std::uint64_t>();
  run.recording = recording;
  return run;
}

}  // namespace palp
