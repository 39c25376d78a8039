// SPDX-License-Identifier: Apache-2.0
// palpctl's shared sweep options and analysis output (sweep_options.hpp).
#include "sweep_options.hpp"

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "palp/identification_result.hpp"
#include "option_alias.hpp"

namespace palpctl {

namespace an = palp::analysis;

namespace {

json read_json_file(const std::string& file, const char* option) {
  const std::string text = palp::format::read_bounded_or(
      file, palp::format::kMaxJsonFileBytes, [&](const std::string& problem) -> void {
        throw palp::RecordingError(file, 0, problem + " (" + option + ")");
      });
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    throw palp::RecordingError(file, 0, std::string("not JSON (") + option + "): " +
                                            palp::format::escaped(e.what(), 240));
  }
}

/// The object holding the analysed numbers: the file itself (`palpctl analyze ... --json`) or
/// its "analysis" (a result.json).
const json& analysed(const json& j) {
  if (j.is_object() && j.contains("analysis") && j["analysis"].is_object()) return j["analysis"];
  return j;
}

double need_number(const json& j, const std::string& key, const std::string& file, const char* option) {
  if (!j.is_object() || !j.contains(key))
    throw palp::RecordingError(file, 0, std::string(option) + ": no \"" + key + "\" in this file");
  const json& v = j[key];
  if (v.is_null()) {
    const std::string why = j.contains(key + "_reason") && j[key + "_reason"].is_string()
                                ? j[key + "_reason"].get<std::string>()
                                : "no reason given";
    throw palp::RecordingError(file, 0, std::string(option) + ": \"" + key + "\" is null (" + why + ")");
  }
  if (!v.is_number()) throw palp::RecordingError(file, 0, std::string(option) + ": \"" + key + "\" is not a number");
  return v.get<double>();
}

struct StaticPoint {
  double k_o_N_per_m = 0, k_o_se_N_per_m = 0, bias_A = 0;
  std::optional<double> delta0_m;
};

StaticPoint read_static(const std::string& file) {
  const json doc = read_json_file(file, "--static");
  const json& j = analysed(doc);
  StaticPoint s;
  s.k_o_N_per_m = need_number(j, "k_tangent_N_per_mm", file, "--static") * 1e3;
  if (j.contains("k_tangent_N_per_mm_se") && j["k_tangent_N_per_mm_se"].is_number())
    s.k_o_se_N_per_m = j["k_tangent_N_per_mm_se"].get<double>() * 1e3;
  if (j.contains("delta0_mm") && j["delta0_mm"].is_number()) s.delta0_m = j["delta0_mm"].get<double>() * 1e-3;
  if (!j.contains("params")) throw palp::RecordingError(file, 0, "--static: no \"params\" (the bias current) in this file");
  s.bias_A = need_number(j["params"], "bias_current_A", file, "--static");
  return s;
}

/// The free-air m_v and b_v, read through free_air_json's own table.
an::FreeAirResult read_freeair(const std::string& file) {
  const json doc = read_json_file(file, "--freeair");
  const json& j = analysed(doc);
  if (!j.is_object() || !j.contains("free_air") || !j["free_air"].is_object())
    throw palp::RecordingError(file, 0,
                               "--freeair: no \"free_air\" object: give the --json output (or result.json) of "
                               "palpctl freeair or palpctl analyze freeair");
  try {
    return palp::free_air_from_json(j);
  } catch (const palp::ConfigError& e) {
    throw palp::RecordingError(file, 0, std::string("--freeair: ") + e.what());
  }
}

}  // namespace

SweepCli SweepCli::of(const palp::IdentificationSettings& s) {
  SweepCli o;
  o.method = palp::sweep_method_name(s.method);
  o.in_contact = s.in_contact;
  o.bias_A = s.bias_A;
  o.amplitude_A = s.amplitude_A;
  o.f_lo_Hz = s.f_lo_Hz;
  o.f_hi_Hz = s.f_hi_Hz;
  o.step_Hz = s.step_Hz;
  o.settle_cycles = s.settle_cycles;
  o.settle_min_s = s.settle_min_s;
  o.measure_cycles = s.measure_cycles;
  o.fundamental_Hz = s.fundamental_Hz;
  o.line_step = s.line_step;
  o.discard_periods = s.discard_periods;
  o.measured_periods = s.measured_periods;
  o.seed = s.phase_seed;
  o.phases = s.phase_mode == palp::proto::PhaseMode::schroeder ? "schroeder" : "random";
  o.rate_Hz = s.stream_rate_Hz;
  o.settle_s = s.settle_s;
  o.ic_A = s.contact_current_A;
  o.kf_N_per_A = s.frf.force_constant_N_per_A;
  o.kv_N_per_mm = s.instrument.k_v_N_per_m * 1e-3;
  o.mv_kg = s.instrument.m_v_kg;
  o.bv_N_s_per_m = s.instrument.b_v_N_s_per_m;
  o.max_excursion_mm = s.max_excursion_m * 1e3;
  return o;
}

palp::IdentificationSettings settings_of(const SweepCli& o) {
  auto s = palp::IdentificationSettings::preset(o.in_contact ? palp::IdentificationPreset::contact_multisine
                                                             : palp::IdentificationPreset::free_air);
  s.method = o.method == "stepped" ? palp::SweepMethod::stepped : palp::SweepMethod::multisine;
  s.bias_A = o.bias_A;
  s.amplitude_A = o.amplitude_A;
  s.f_lo_Hz = o.f_lo_Hz;
  s.f_hi_Hz = o.f_hi_Hz;
  s.step_Hz = o.step_Hz;
  s.settle_cycles = o.settle_cycles;
  s.settle_min_s = o.settle_min_s;
  s.measure_cycles = o.measure_cycles;
  s.fundamental_Hz = o.fundamental_Hz;
  s.line_step = o.line_step;
  s.discard_periods = o.discard_periods;
  s.measured_periods = o.measured_periods;
  s.phase_seed = o.seed;
  s.phase_mode = o.phases == "schroeder" ? palp::proto::PhaseMode::schroeder : palp::proto::PhaseMode::random_seeded;
  s.stream_rate_Hz = o.rate_Hz;
  s.settle_s = o.settle_s;
  s.contact_current_A = o.ic_A;
  s.frf.force_constant_N_per_A = o.kf_N_per_A;
  s.instrument.k_v_N_per_m = o.kv_N_per_mm * 1e3;
  s.instrument.m_v_kg = o.mv_kg;
  s.instrument.b_v_N_s_per_m = o.bv_N_s_per_m;
  s.max_excursion_m = o.max_excursion_mm * 1e-3;
  return s;
}

void add_program_options(CLI::App* cmd, SweepCli& o) {
  cmd->add_option("--method", o.method,
                  "stepped: the paper's stepped sine (settle, then whole cycles per line); multisine: "
                  "periodic multisine, every line_step-th line excited, a tenth of the time")
      ->check(CLI::IsMember({"stepped", "multisine"}))
      ->capture_default_str();
  add_hidden_alias(*cmd,
                   cmd->add_option("--bias-current-A", o.bias_A, "Bias current I_0, A")
                       ->check(CLI::Range(-4.0, 4.0))->capture_default_str(),
                   "--bias-A");
  cmd->add_option("--amplitude-A", o.amplitude_A,
                  "Peak excitation about the bias, A (a multisine's true waveform peak)")
      ->check(CLI::Range(0.0001, 4.0))->capture_default_str();
  add_hidden_alias(*cmd, cmd->add_option("--start-Hz", o.f_lo_Hz, "Lowest line, Hz")->check(kPositive)->capture_default_str(),
                   "--f-lo-Hz");
  add_hidden_alias(*cmd, cmd->add_option("--stop-Hz", o.f_hi_Hz, "Highest line, Hz")->check(kPositive)->capture_default_str(),
                   "--f-hi-Hz");
  cmd->add_option("--step-Hz", o.step_Hz, "Stepped sine: line spacing, Hz")->check(kPositive)->capture_default_str();
  cmd->add_option("--settle-cycles", o.settle_cycles, "Stepped sine: cycles discarded per line (at least)")
      ->check(CLI::Range(0, 10000))->capture_default_str();
  cmd->add_option("--settle-min-s", o.settle_min_s, "Stepped sine: settle at least this long per line, s")
      ->check(CLI::Range(0.0, 100.0))->capture_default_str();
  cmd->add_option("--measure-cycles", o.measure_cycles, "Stepped sine: cycles measured per line")
      ->check(CLI::Range(1, 10000))->capture_default_str();
  cmd->add_option("--fundamental-Hz", o.fundamental_Hz, "Multisine: 1 / period, Hz")
      ->check(kPositive)->capture_default_str();
  cmd->add_option("--line-step", o.line_step, "Multisine: excite every n-th line (4: lines 4k+1)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--discard-periods", o.discard_periods, "Multisine: transient periods dropped")
      ->check(CLI::Range(0, 100))->capture_default_str();
  cmd->add_option("--measured-periods", o.measured_periods, "Multisine: periods averaged (>= 2 for a noise estimate)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--seed", o.seed, "Multisine: random-phase seed (non-zero)")
      ->check(CLI::Range(1u, 0xFFFFFFFFu))->capture_default_str();
  cmd->add_option("--phases", o.phases, "Multisine: random or schroeder phases")
      ->check(CLI::IsMember({"random", "schroeder"}))->capture_default_str();
  cmd->add_option("--rate-Hz", o.rate_Hz, "Stream rate, Hz (at most 1000, dividing the control rate)")
      ->check(CLI::Range(1.0, 1000.0))->capture_default_str();
  cmd->add_option("--settle-s", o.settle_s, "Device time at the bias before the excitation, s")
      ->check(CLI::Range(0.0, 60.0))->capture_default_str();
  cmd->add_option("--ic-A", o.ic_A, "Contact threshold current I_c, A")->check(CLI::Range(-4.0, 4.0))->capture_default_str();
  cmd->add_option("--kf-N-per-A", o.kf_N_per_A, "Force constant K_f, N/A (F = K_f I)")
      ->check(kPositive)->capture_default_str();
  cmd->add_option("--kv-N-per-mm", o.kv_N_per_mm, "Return springs k_v, N/mm")->check(kPositive)->capture_default_str();
  cmd->add_option("--max-excursion-mm", o.max_excursion_mm,
                  "Free air: refuse settings whose predicted peak excursion exceeds this, mm")
      ->check(kPositive)->capture_default_str();
}

void add_analysis_options(CLI::App* cmd, SweepCli& o) {
  cmd->add_option("--static", o.static_file,
                  "The quasi-static result at the same bias (the --json output of palpctl analyze "
                  "indentation, or an indent result.json): k_o and delta0 for the decomposition and "
                  "the moduli");
  cmd->add_option("--freeair", o.freeair_file,
                  "The free-air result (--json of palpctl freeair or analyze freeair): m_v and b_v "
                  "instead of --mv-kg / --bv-N-s-per-m");
  cmd->add_option("--mv-kg", o.mv_kg, "Instrument moving mass m_v, kg")->check(kPositive)->capture_default_str();
  cmd->add_option("--bv-N-s-per-m", o.bv_N_s_per_m, "Instrument damping b_v, N s/m")
      ->check(kNonNegative)->capture_default_str();
  cmd->add_option("--tip-radius-mm", o.tip_radius_mm, "Tip radius R for the moduli, mm")
      ->check(kPositive)->capture_default_str();
}

json analysis_json(const SweepCli& o, const an::Frf& frf, const an::SecondOrderFit& fit,
                   std::optional<double> bias_A, bool free_air) {
  an::InstrumentDynamics inst{o.mv_kg, o.bv_N_s_per_m, o.kv_N_per_mm * 1e3};
  json params = {{"kf_N_per_A", o.kf_N_per_A}, {"kv_N_per_mm", o.kv_N_per_mm}};
  if (bias_A) params["bias_A"] = *bias_A;
  if (!o.input.empty()) params["input"] = o.input;
  if (!free_air) {
    if (!o.freeair_file.empty()) {
      const auto fa = read_freeair(o.freeair_file);
      inst.m_v_kg = fa.m_v_kg;
      inst.b_v_N_s_per_m = fa.b_v_N_s_per_m;
      params["freeair"] = o.freeair_file;
    }
    params["mv_kg"] = inst.m_v_kg;
    params["bv_N_s_per_m"] = inst.b_v_N_s_per_m;
  }
  json j = {{"params", params}};
  j.update(palp::sweep_summary_json(frf, fit));
  if (free_air) {
    const auto fa = an::free_air_from(fit.omega_n_rad_per_s, fit.zeta, inst.k_v_N_per_m,
                                      fit.omega_n_rad_per_s_se, fit.zeta_se);
    j["free_air"] = palp::free_air_json(fa);
    return j;
  }
  if (o.static_file.empty()) {
    for (const char* k : {"m_eff_kg", "b_o_N_s_per_m"}) {
      j[k] = nullptr;
      j[std::string(k) + "_reason"] = "no --static result: the static k_o is needed";
    }
    return j;
  }
  const StaticPoint st = read_static(o.static_file);
  j["params"]["static"] = o.static_file;
  if (bias_A && std::abs(st.bias_A - *bias_A) > 1e-6)
    throw palp::ConfigError("--static " + o.static_file + " gives k_o at a bias of " + fmt(st.bias_A) +
                            " A but the sweep ran at I_0 = " + fmt(*bias_A) +
                            " A: analyse the indentation again with --bias-current-A " + fmt(*bias_A));
  if (!bias_A) j["params"]["bias_check"] = "the input gives no bias current: --static's bias was not checked";
  const auto d = an::decompose(fit, st.k_o_N_per_m, inst, st.k_o_se_N_per_m);
  j.update(palp::decomposition_json(d));  // m_eff_kg, b_o_N_s_per_m ... at the top level
  if (st.delta0_m && !frf.lines.empty()) {
    j["viscoelastic"] = palp::viscoelastic_json(an::viscoelastic_from(frf.lines, inst, *st.delta0_m, o.tip_radius_mm * 1e-3));
  } else {
    j["viscoelastic"] = nullptr;
    j["viscoelastic_reason"] = "the --static file gives no delta0_mm";
  }
  return j;
}

void print_analysis(const json& j) {
  static const char* keys[] = {"method", "lines", "line_spacing_Hz", "device_time_s", "omega_n_rad_per_s",
                               "omega_n_rad_per_s_se", "f_n_Hz", "zeta", "zeta_se", "m_kg", "b_N_s_per_m",
                               "k_N_per_mm", "normalized_cost", "adequate", "k_eff_N_per_mm", "m_eff_kg",
                               "b_total_N_s_per_m", "b_o_N_s_per_m", "b_o_N_s_per_m_reason"};
  json out = json::object();
  for (const char* k : keys)
    if (j.contains(k)) out[k] = j[k];
  if (j.contains("free_air")) out["free_air"] = j["free_air"];
  if (j.contains("distortion") && j["distortion"].is_object()) {
    out["distortion_even_ratio"] = j["distortion"]["even_ratio"];
    out["distortion_odd_ratio"] = j["distortion"]["odd_ratio"];
  }
  print_text(out);
  if (j.contains("notes"))
    for (const auto& n : j["notes"]) std::cout << "note: " << n.get<std::string>() << '\n';
  if (j.contains("distortion") && j["distortion"].is_object() && j["distortion"]["too_large"].get<bool>())
    std::cout << "warning: " << j["distortion"]["warning"].get<std::string>() << '\n';
  if (j.contains("viscoelastic") && j["viscoelastic"].is_object() && j["viscoelastic"]["flagged"].get<bool>())
    std::cout << "moduli flagged: " << j["viscoelastic"]["flag_reason"].get<std::string>() << '\n';
}

}  // namespace palpctl
