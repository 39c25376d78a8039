// SPDX-License-Identifier: Apache-2.0
// Result directories (issue 6): every experiment writes one directory, atomically, that holds
// everything needed to understand and re-analyse it. The layout, for people and other programs,
// is docs/result-format.md:
//
//   results/solid-p3/
//     result.json        schema "palp.result/1": experiment, created_utc, sdk_version, device
//                        and firmware, every parameter (lab units), the run's outcome, the
//                        analysed numbers in lab units (the keys of `palpctl ... --json`) and
//                        the pressure channels against force
//     indentation.csv    the recording (recording.hpp, docs/recording-format.md)
//     indentation.json   its sidecar
//
//   palp::write_result("results/solid-p3", run);            // appears whole, or not at all
//   palp::LoadedResult r = palp::load_result("results/solid-p3");
//   double d0 = r.summary["analysis"]["delta0_mm"];          // null + delta0_mm_reason if absent
//   palp::IndentationRun again = palp::indentation_run_of(r); // re-analysable
//
// Atomicity: the files are written into a hidden sibling directory (`.solid-p3.tmp-<pid>-<n>`),
// flushed to disk, and the directory is renamed into place: a crash leaves either no result
// directory or a complete one (and at most a hidden temporary one, which can be deleted).
// Overwrite::yes replaces only a directory palp wrote: every result directory holds
// `.palp-files`, the list of the files palp wrote into it, and an existing directory is replaced
// only when it has that list and nothing the list does not name (else ConfigError naming the
// path that is not palp's); it is moved aside, and only the listed files are deleted after the
// rename.
//
// Errors: a missing or malformed result is a RecordingError naming the file (result.json, or the
// recording) and the problem; wrong arguments (an existing directory without Overwrite::yes, a
// run without samples) are ConfigError.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/analysis/indentation.hpp"
#include "palp/indent.hpp"
#include "palp/probe.hpp"
#include "palp/recording.hpp"

namespace palp {

/// result.json's "schema". The reader accepts version 1.
inline constexpr std::string_view kResultSchema = "palp.result/1";
/// The summary's file name inside a result directory.
inline constexpr std::string_view kResultFile = "result.json";

/// Writes an indentation run as a result directory (`indentation.csv` + `.json`, result.json).
/// Returns the directory's final path.
std::filesystem::path write_result(const std::filesystem::path& dir, const IndentationRun& run,
                                   Overwrite overwrite = Overwrite::no);

/// Whether a writer with Overwrite::yes may replace `dir`: it is absent, or it is a directory
/// holding `.palp-files` and nothing that list does not name. Otherwise ConfigError naming the
/// path that is not palp's (the directory when it has no list, else its first unknown entry).
/// The writers check it themselves; call it first to refuse before the device moves.
void check_replaceable(const std::filesystem::path& dir);

/// A result directory read back.
struct LoadedResult {
  std::filesystem::path dir;
  nlohmann::json summary;             ///< result.json as written
  std::string experiment;             ///< "indentation"
  /// The recordings result.json lists, by their file name ("indentation.csv"), read with their
  /// sidecars (which must match their CSVs).
  std::vector<std::pair<std::string, Recording>> recordings;
};

/// Reads a result directory. Throws RecordingError naming the file: no result.json, invalid
/// JSON, another schema, a missing key, a listed recording that is missing or malformed.
LoadedResult load_result(const std::filesystem::path& dir);

/// An indentation run rebuilt from a loaded result: its settings (from result.json's
/// "parameters"), its recording and device, analysed again with analyze_run. Throws
/// RecordingError when the result is not an indentation or its parameters are incomplete.
IndentationRun indentation_run_of(const LoadedResult& result);

// --- JSON in lab units (the keys carry their units) ---------------------------------------------

/// The analysed numbers with the keys: params (the inputs echoed), contact_point_mm,
/// k_linear_N_per_mm, r2_linear, E_star_hertz_Pa, r2_hertz, E_star_sneddon_Pa, r2_sneddon,
/// model_by_aic, delta0_mm, k_tangent_N_per_mm, k_fd_N_per_mm, k_ls_window_N_per_mm,
/// k_fd_paper_N_per_mm, k_at_depth_N_per_mm ("1_mm".. per tangent depth); every estimate with
/// `<key>_se` (the fit's standard error; for delta0 and the tangents the delta method through
/// the chosen model's k or E*; null + `<key>_se_reason` for the model-free ones) and, when
/// `reps` is given, `<key>_sd` over repetitions (null + `<key>_sd_reason` below two). A value
/// that cannot be computed is null with `<key>_reason`. Also E_hertz_Pa / E_sneddon_Pa
/// (E = E* (1 - nu^2)), n_loading, n_unloading, F0_N, has_baseline, repetitions (the count) and
/// the per-model AIC (aic_linear, ...). The same keys as `palpctl analyze indentation --json`.
nlohmann::json indentation_summary_json(const analysis::IndentationResult& result,
                                        const analysis::RepetitionSummary* reps,
                                        const analysis::IndentationParams& params);
/// The pressure–force test as `palpctl analyze pressure --json` gives it: contact_point_mm,
/// n_loading, channels [{channel, slope_Pa_per_N (+ _se), intercept_Pa, r2, rise_Pa, rise_Pa_sd,
/// hysteresis_ratio, hysteresis_per_rep [{loop_area_Pa_N, ratio, max_gap_Pa}]}].
nlohmann::json pressure_summary_json(const analysis::PressureResult& result);
/// The analysis inputs as the CLI names them: kf_N_per_A, ic_A, kv_N_per_mm, tip_radius_mm,
/// poisson, bias_current_A, bias_force_N, thickness_mm (null when none) and bonding, window_lo_mm,
/// window_hi_mm, local_half_width_mm, tangent_depths_mm, min_points.
nlohmann::json indentation_params_json(const analysis::IndentationParams& p);
/// The experiment's settings (ramp in A and s, limit in mm, rates in Hz) and its analysis params,
/// result.json's "parameters".
nlohmann::json indentation_settings_json(const IndentationSettings& s);
/// indentation_settings_json read back (keys it does not know are ignored; unload, zero_pressure,
/// zero_pressure_s, settle_s, min_points, tangent_depths_mm and force_noise_N keep their defaults
/// when absent). ConfigError "missing key \"<where>start_A\"", "\"<where>analysis.poisson\" is not
/// a number", ...
IndentationSettings indentation_settings_from_json(const nlohmann::json& j, const std::string& where = "");
/// The device block of the sidecar and result.json (and `palpctl info`): serial, board,
/// firmware_version, git_hash, protocol ("major.minor"), schema_hash, capabilities (the
/// proto::Capability bits), max_current_A, control_rate_Hz, max_stream_rate_Hz,
/// heartbeat_timeout_s, max_payload_bytes.
nlohmann::json device_json(const DeviceInfo& d);
/// A device block read back (other keys, such as the sidecar's "uri", are ignored). Every key may
/// be absent; a block palpctl wrote before issue 16 ("protocol_version", and "simulated" and
/// "pressure_channels" instead of "capabilities") reads too. ConfigError "where: \"key\" ..."
/// for a key of the wrong type.
DeviceInfo device_info_from_json(const nlohmann::json& j, const std::string& where);
/// The calibration (lab units) and a zeroing record, as in the sidecar.
nlohmann::json calibration_json(const Calibration& c);
nlohmann::json zeroing_json(const ZeroingRecord& z);
/// A device program's parameters as the sidecar's program.parameters holds them, in lab units
/// (each f32 as its shortest decimal): hold current_A, seconds; ramp start_A, stop_A, step_A,
/// dwell_s, reps, unload, displacement_limit_mm; sine offset_A, amplitude_A, frequency_Hz,
/// cycles; sweep and multisine the message's own field names (phase_mode by its name).
nlohmann::json program_json(const HoldProgram& m);
nlohmann::json program_json(const RampProgram& m);
nlohmann::json program_json(const SineProgram& m);
nlohmann::json program_json(const SweepProgram& m);
nlohmann::json program_json(const MultisineProgram& m);
/// program_json read back into `m` (the same keys; others are ignored). ConfigError
/// "where: \"key\" must be a number", ... for a missing or mistyped key.
void read_program(const nlohmann::json& parameters, const std::string& where, HoldProgram& m);
void read_program(const nlohmann::json& parameters, const std::string& where, RampProgram& m);
void read_program(const nlohmann::json& parameters, const std::string& where, SineProgram& m);
void read_program(const nlohmann::json& parameters, const std::string& where, SweepProgram& m);
void read_program(const nlohmann::json& parameters, const std::string& where, MultisineProgram& m);
/// The device's state in lab units, as the sidecar and `palpctl --json` write it (keys carry
/// their units, enums by their catalogue names):
///   params_json:  current_clamp_A, i2t_continuous_A, i2t_limit_A2_s, i2t_tau_s, travel_min_mm,
///                 travel_max_mm, heartbeat_timeout_s, control_rate_Hz, supply_V,
///                 contact_output, contact_output_hold_s (the sidecar's device.params);
///   health_json:  {"device": {time_s, frames_rx, ...} or null, "host": {frames_rx, ...}} and
///                 device_reason when no Health reply came (the sidecar's health);
///   fault_json:   reason, latched, t_device_s, detail, text;
///   program_result_json: program, end, t_device_s, repetitions_done (program.result).
nlohmann::json params_json(const Params& p);
nlohmann::json health_json(const HealthCounters& h);
nlohmann::json fault_json(const FaultInfo& f);
nlohmann::json program_result_json(const ProgramResult& r);
/// What the device and the SDK know before the first sample, for a recording's sidecar: the SDK
/// version, device (device_json with "uri"), calibration, stroke_origin_z_mm (or its reason),
/// zeroing and, in extra, "stream" (rate_Hz, period_s, channels, batch_samples of the configured
/// stream). The experiments and palpctl's recordings start from it.
Sidecar setup_sidecar(Probe& probe);

}  // namespace palp
