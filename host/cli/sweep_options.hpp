// SPDX-License-Identifier: Apache-2.0
// The options palpctl freeair, sweep and analyze sweep share (lab units in every name) and the
// analysis they print: the fit, and with --static / --freeair the paper's decomposition and the
// moduli (palp/identification_result.hpp has the JSON keys).
#pragma once

#include <optional>
#include <string>

#include "common.hpp"
#include "palp/identification.hpp"

namespace palpctl {

struct SweepCli {
  std::string method = "multisine";
  double bias_A = 1.0, amplitude_A = 0.1, f_lo_Hz = 2.0, f_hi_Hz = 20.0;
  double step_Hz = 0.05, settle_min_s = 1.2;
  int settle_cycles = 3, measure_cycles = 5;
  double fundamental_Hz = 0.05;
  int line_step = 4, discard_periods = 1, measured_periods = 2;
  std::uint32_t seed = 1;
  std::string phases = "random";
  double rate_Hz = 1000, settle_s = 1.2;
  double ic_A = 0.5, kf_N_per_A = 2.918, kv_N_per_mm = 0.0439;
  double mv_kg = 0.1609, bv_N_s_per_m = 1.379, max_excursion_mm = 3.0, tip_radius_mm = 2.5;
  bool in_contact = true;
  // analysis inputs
  std::string static_file, freeair_file;
  // device commands
  std::string out_dir;
  bool overwrite = false;
  // analyze sweep
  std::string input;
  double control_rate_Hz = 20000;

  /// The defaults of a preset, in lab units.
  static SweepCli of(const palp::IdentificationSettings& s);
};

/// The program and instrument options (device and analyze commands alike).
void add_program_options(CLI::App* cmd, SweepCli& o);
/// --static, --freeair, --mv-kg, --bv-N-s-per-m, --tip-radius-mm.
void add_analysis_options(CLI::App* cmd, SweepCli& o);

/// The settings the options give (the preset's in_contact flag kept).
palp::IdentificationSettings settings_of(const SweepCli& o);

/// The printed analysis: params (the inputs echoed), sweep_summary_json, and
///   free air: free_air (m_v, b_v with k_v), and m_kg / b_N_s_per_m from it as the paper's;
///   contact with --static: decomposition (m_eff_kg, b_o_N_s_per_m, ...) and viscoelastic.
/// bias_A: the sweep's I_0 when known (a --static at another bias is refused), else nullopt.
json analysis_json(const SweepCli& o, const palp::analysis::Frf& frf,
                   const palp::analysis::SecondOrderFit& fit, std::optional<double> bias_A,
                   bool free_air);

/// The human form of analysis_json: the headline numbers, one per line.
void print_analysis(const json& j);

}  // namespace palpctl
