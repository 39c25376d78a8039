// Dynamic identification (identification.hpp): float the coil, hold the bias, run the stepped
// sine or the multisine while recording, analyse; and the re-analysis of a loaded recording.
#include <algorithm>
#include <cmath>
#include <string>

#include "experiment_common.hpp"
#include "palp/error.hpp"
#include "palp/identification.hpp"

namespace palp {

namespace {

using experiment::f32;

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

nlohmann::json sweep_json(const proto::LoadSweep& m) {
  return {{"offset_A", f32(m.offset_A)},         {"amplitude_A", f32(m.amplitude_A)},
          {"start_Hz", f32(m.start_Hz)},         {"stop_Hz", f32(m.stop_Hz)},
          {"step_Hz", f32(m.step_Hz)},           {"settle_cycles", m.settle_cycles},
          {"settle_min_s", f32(m.settle_min_s)}, {"measure_cycles", m.measure_cycles}};
}

nlohmann::json multisine_json(const proto::LoadMultisine& m) {
  const char* mode = proto::enum_name(m.phase_mode);
  return {{"offset_A", f32(m.offset_A)},
          {"fundamental_Hz", f32(m.fundamental_Hz)},
          {"line_first", m.line_first},
          {"line_last", m.line_last},
          {"line_step", m.line_step},
          {"line_amplitude_A", f32(m.line_amplitude_A)},
          {"phase_mode", mode ? mode : "?"},
          {"phase_seed", m.phase_seed},
          {"periods", m.periods}};
}

proto::PhaseMode phase_mode_named(const std::string& name, const std::string& where) {
  for (const auto& v : proto::EnumInfo<proto::PhaseMode>::values)
    if (name == v.name) return static_cast<proto::PhaseMode>(v.value);
  throw ConfigError(where + ": unknown phase_mode \"" + name +
                    "\" (random_seeded, schroeder or zero)");
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

}  // namespace

nlohmann::json identification_settings_json(const IdentificationSettings& s) {
  nlohmann::json table = nlohmann::json::array();
  for (std::size_t k = 0; k < s.frf.kf_table_stroke_m.size() && k < s.frf.kf_table_N_per_A.size(); ++k)
    table.push_back({{"position_mm", s.frf.kf_table_stroke_m[k] * 1e3},
                     {"kf_N_per_A", s.frf.kf_table_N_per_A[k]}});
  return {{"method", sweep_method_name(s.method)},
          {"in_contact", s.in_contact},
          {"bias_A", s.bias_A},
          {"amplitude_A", s.amplitude_A},
          {"f_lo_Hz", s.f_lo_Hz},
          {"f_hi_Hz", s.f_hi_Hz},
          {"step_Hz", s.step_Hz},
          {"settle_cycles", s.settle_cycles},
          {"settle_min_s", s.settle_min_s},
          {"measure_cycles", s.measure_cycles},
          {"fundamental_Hz", s.fundamental_Hz},
          {"line_step", s.line_step},
          {"discard_periods", s.discard_periods},
          {"measured_periods", s.measured_periods},
          {"phase_seed", s.phase_seed},
          {"phase_mode", proto::enum_name(s.phase_mode) ? proto::enum_name(s.phase_mode) : "?"},
          {"stream_rate_Hz", s.stream_rate_Hz},
          {"settle_s", s.settle_s},
          {"contact_current_A", s.contact_current_A},
          {"max_excursion_mm", s.max_excursion_m * 1e3},
          {"kf_N_per_A", s.frf.force_constant_N_per_A},
          {"kf_table", table},
          {"kf_table_stroke_origin_z_mm", s.frf.stroke_origin_z_m * 1e3},
          {"distortion_limit", s.frf.distortion_limit},
          {"instrument",
           {{"m_v_kg", s.instrument.m_v_kg},
            {"b_v_N_s_per_m", s.instrument.b_v_N_s_per_m},
            {"k_v_N_per_mm", s.instrument.k_v_N_per_m * 1e-3}}},
          {"fit",
           {{"sk_iterations", s.fit.sk_iterations},
            {"max_lm_iterations", s.fit.max_lm_iterations},
            {"adequate_cost", s.fit.adequate_cost}}}};
}

IdentificationSettings identification_settings_from_json(const nlohmann::json& j) {
  const Reader r{j, "the identification settings"};
  IdentificationSettings s;
  const std::string method = r.str("method");
  if (method != "stepped" && method != "multisine")
    throw ConfigError("the identification settings: method \"" + method +
                      "\" is neither stepped nor multisine");
  s.method = method == "stepped" ? SweepMethod::stepped : SweepMethod::multisine;
  s.in_contact = r.boolean("in_contact");
  s.bias_A = r.num("bias_A");
  s.amplitude_A = r.num("amplitude_A");
  s.f_lo_Hz = r.num("f_lo_Hz");
  s.f_hi_Hz = r.num("f_hi_Hz");
  s.step_Hz = r.num("step_Hz");
  s.settle_cycles = r.integer<int>("settle_cycles");
  s.settle_min_s = r.num("settle_min_s");
  s.measure_cycles = r.integer<int>("measure_cycles");
  s.fundamental_Hz = r.num("fundamental_Hz");
  s.line_step = r.integer<int>("line_step");
  s.discard_periods = r.integer<int>("discard_periods");
  s.measured_periods = r.integer<int>("measured_periods");
  s.phase_seed = r.integer<std::uint32_t>("phase_seed");
  s.phase_mode = phase_mode_named(r.str("phase_mode"), r.where);
  s.stream_rate_Hz = r.num("stream_rate_Hz");
  s.settle_s = r.num("settle_s");
  s.contact_current_A = r.num("contact_current_A");
  s.max_excursion_m = r.num("max_excursion_mm") * 1e-3;
  s.frf.force_constant_N_per_A = r.num("kf_N_per_A");
  const auto& table = r.at("kf_table");
  if (!table.is_array()) throw ConfigError("the identification settings: \"kf_table\" is not an array");
  for (const auto& row : table) {
    const Reader t{row, "the identification settings' kf_table row"};
    s.frf.kf_table_stroke_m.push_back(t.num("position_mm") * 1e-3);
    s.frf.kf_table_N_per_A.push_back(t.num("kf_N_per_A"));
  }
  s.frf.stroke_origin_z_m = r.num("kf_table_stroke_origin_z_mm") * 1e-3;
  s.frf.distortion_limit = r.num("distortion_limit");
  s.frf.multisine_discard_periods = s.discard_periods;
  const Reader in{r.at("instrument"), "the identification settings' instrument"};
  s.instrument.m_v_kg = in.num("m_v_kg");
  s.instrument.b_v_N_s_per_m = in.num("b_v_N_s_per_m");
  s.instrument.k_v_N_per_m = in.num("k_v_N_per_mm") * 1e3;
  const Reader fit{r.at("fit"), "the identification settings' fit"};
  s.fit.sk_iterations = fit.integer<int>("sk_iterations");
  s.fit.max_lm_iterations = fit.integer<int>("max_lm_iterations");
  s.fit.adequate_cost = fit.num("adequate_cost");
  return s;
}

IdentificationRun identify(Probe& probe, const IdentificationSettings& settings,
                           const IdentifyProgressFn& progress, const std::function<bool()>& cancelled) {
  settings.validate();
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

  Sidecar side = experiment::base_sidecar(probe, run.device, "identification", rec);
  side.program = {{"kind", stepped ? "sweep" : "multisine"},
                  {"parameters", stepped ? sweep_json(run.sweep) : multisine_json(run.multisine)},
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
  } catch (const ConfigError& e) {
    run.analysis_reason = std::string("no frequency response: ") + e.what();
    return;
  }
  try {
    run.fit = analysis::fit_second_order(run.frf->lines, run.settings.fit);
  } catch (const ConfigError& e) {
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
  const Reader p{program.at("parameters"), "the recording's sidecar program parameters"};
  const bool stepped = run.settings.method == SweepMethod::stepped;
  if (kind != (stepped ? "sweep" : "multisine"))
    throw ConfigError("the recording's sidecar program is a \"" + kind + "\", the settings' method " +
                      sweep_method_name(run.settings.method) + " needs a " +
                      (stepped ? "sweep" : "multisine"));
  if (stepped) {
    proto::LoadSweep& m = run.sweep;
    m.offset_A = static_cast<float>(p.num("offset_A"));
    m.amplitude_A = static_cast<float>(p.num("amplitude_A"));
    m.start_Hz = static_cast<float>(p.num("start_Hz"));
    m.stop_Hz = static_cast<float>(p.num("stop_Hz"));
    m.step_Hz = static_cast<float>(p.num("step_Hz"));
    m.settle_cycles = p.integer<std::uint16_t>("settle_cycles");
    m.settle_min_s = static_cast<float>(p.num("settle_min_s"));
    m.measure_cycles = p.integer<std::uint16_t>("measure_cycles");
  } else {
    proto::LoadMultisine& m = run.multisine;
    m.offset_A = static_cast<float>(p.num("offset_A"));
    m.fundamental_Hz = static_cast<float>(p.num("fundamental_Hz"));
    m.line_first = p.integer<std::uint16_t>("line_first");
    m.line_last = p.integer<std::uint16_t>("line_last");
    m.line_step = p.integer<std::uint16_t>("line_step");
    m.line_amplitude_A = static_cast<float>(p.num("line_amplitude_A"));
    m.phase_mode = phase_mode_named(p.str("phase_mode"), p.where);
    m.phase_seed = p.integer<std::uint32_t>("phase_seed");
    m.periods = p.integer<std::uint16_t>("periods");
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
