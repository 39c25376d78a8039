// SPDX-License-Identifier: Apache-2.0
// What an identification gives, in lab units with the unit in every key (issue 7): the summary
// `palpctl sweep|freeair|analyze sweep --json` prints and result.json holds, the frequency
// response as a table `palpctl analyze sweep` reads back, and the result directory.
//
//   results/solid-p3-multisine/
//     result.json   schema "palp.result/1", experiment "identification": parameters, run,
//                   analysis (sweep_summary_json), and free_air / decomposition when known
//     sweep.csv     the recording (recording.hpp), sweep.json its sidecar
//     frf.csv       the measured response: f_Hz,re_m_per_N,im_m_per_N,sigma_m_per_N
//                   (frf_table.hpp reads it)
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "palp/analysis/dynamics.hpp"
#include "palp/analysis/frf.hpp"
#include "palp/analysis/second_order.hpp"
#include "palp/identification.hpp"
#include "palp/recording.hpp"

namespace palp {

/// The measurement and the fit: method, lines, line_spacing_Hz, f_lo_Hz, f_hi_Hz,
/// device_time_s, notes; omega_n_rad_per_s, f_n_Hz, zeta, m_kg, b_N_s_per_m, k_N_per_mm, each
/// with `<key>_se`; normalized_cost (null + normalized_cost_reason without noise estimates),
/// adequate, fit_converged, distortion (multisine: even_ratio, odd_ratio, excited_rms_mm,
/// even_rms_mm, odd_rms_mm, noise_rms_mm, too_large, warning) or null + distortion_reason.
nlohmann::json sweep_summary_json(const analysis::Frf& frf, const analysis::SecondOrderFit& fit);

// Each summary's keys are one field table (host/src/format/field_table.hpp) that the writer and
// the reader share; a number that is not finite is written null with `<key>_reason`.

/// Free air: omega_n_rad_per_s, zeta, kv_N_per_mm, m_v_kg, b_v_N_s_per_m, each estimate with _se.
nlohmann::json free_air_json(const analysis::FreeAirResult& r);
/// The free-air result back from an analysis holding "free_air" (free_air_json's object): the
/// --json output of palpctl freeair / analyze freeair, or a result.json's "analysis". A null
/// number reads as NaN, as it was before writing, but m_v and b_v, the instrument's values a
/// free-air result exists to give, must be numbers. ConfigError naming the key ("missing key
/// \"free_air.m_v_kg\"", "\"free_air.zeta\" is not a number", "\"free_air.m_v_kg\" is null
/// (not finite)": the file's `<key>_reason`).
analysis::FreeAirResult free_air_from_json(const nlohmann::json& analysis);

/// Contact: k_o_N_per_mm, k_eff_N_per_mm, m_eff_kg, b_total_N_s_per_m, b_o_N_s_per_m, m_o_kg
/// (with _se where known) and m_eff_note (m_eff = k_eff / omega_n^2, as the paper computes it).
nlohmann::json decomposition_json(const analysis::Decomposition& d);
/// The decomposition back from the object decomposition_json's keys were merged into (palpctl's
/// analysis); ConfigError naming the key as free_air_from_json does.
analysis::Decomposition decomposition_from_json(const nlohmann::json& analysis);

/// The moduli: delta0_mm, tip_radius_mm, contact_radius_mm, flagged (+ flag_reason), lines
/// [{f_Hz, k_storage_N_per_mm, k_loss_N_per_mm, E_storage_Pa, E_loss_Pa, tan_delta}].
nlohmann::json viscoelastic_json(const analysis::Viscoelastic& v);
/// The moduli back from an analysis holding "viscoelastic" (viscoelastic_json's object);
/// ConfigError naming the key ("missing key \"viscoelastic.lines[0].f_Hz\"").
analysis::Viscoelastic viscoelastic_from_json(const nlohmann::json& analysis);

/// The response as CSV (f_Hz,re_m_per_N,im_m_per_N,sigma_m_per_N; shortest round-trip numbers).
std::string format_frf_table(const analysis::Frf& frf);

/// Writes a run as a result directory (layout above), atomically as write_result does.
/// `analysis` is what result.json's "analysis" holds (sweep_summary_json plus whatever the
/// caller adds: free_air, decomposition); null when the run was not analysed. ConfigError for a
/// run without samples or an existing directory without Overwrite::yes.
std::filesystem::path write_identification_result(const std::filesystem::path& dir,
                                                  const IdentificationRun& run,
                                                  const nlohmann::json& analysis,
                                                  Overwrite overwrite = Overwrite::no);

/// The K_f calibration's result, one definition for `palpctl calibrate kf --json` and Python's
/// KfCalibrationRun.to_dict(): calibrate ("kf"), balance (the fitted equation), kv_N_per_mm,
/// levels (settled levels fitted), nodes [{stroke_mm, kf_N_per_A, kf_N_per_A_se}], c_N, c_N_se,
/// residual_rms_N, anchor ({stroke_mm, kf_N_per_A} or null), warning ("" when none), written,
/// committed.
nlohmann::json kf_calibration_json(const KfCalibrationRun& run);

}  // namespace palp
