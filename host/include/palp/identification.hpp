// SPDX-License-Identifier: Apache-2.0
// Dynamic identification (issue 7; paper §III-A, §III-C, §IV-B): the probe's frequency response
// in free air or in contact, by the paper's stepped sine or by a periodic multisine that takes a
// tenth of the time, and the force-constant calibration.
//
//   palp::Probe probe("sim://127.0.0.1:7070");
//   auto s = palp::IdentificationSettings::preset(palp::IdentificationPreset::contact_multisine);
//   palp::IdentificationRun run = palp::identify(probe, s, progress);
//   if (run.fit) use(run.fit->omega_n_rad_per_s, run.fit->zeta);
//
// identify() at the current position, in this order:
//   0. check the settings (validate(), then check_excitation() at the device's control rate)
//      before the device does anything: in contact, the excitation's true peak must stay above
//      the contact threshold, bias_A - peak > I_c (for a multisine, the waveform's own peak); in
//      free air, the peak excursion predicted from `instrument` and K_f over the band must stay
//      within max_excursion_m (3 mm). Refusals are ConfigError with the numbers;
//   1. release the coil if a program or contact hold carries current (settle_s at 0 A);
//   2. float the coil at the contact threshold (a contact watch, as indent() does), then hold the
//      bias with a second contact watch that fires on the first micrometre the step moves the
//      coil (a fired watch keeps its current on until the next program starts), for settle_s;
//   3. run the device program (LoadSweep or LoadMultisine) while recording the stream (every
//      sample the program drives, at stream_rate_Hz);
//   4. back to 0 A; the nonparametric response (frequency_response.hpp) and the second-order fit
//      (second_order.hpp) from the recording.
// Errors as indent(): ConfigError before the device does anything, FaultError/DeviceError from
// the device with the coil left at 0 A; cancellation returns what was recorded, `interrupted`.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "palp/analysis/dynamics.hpp"
#include "palp/analysis/frequency_response.hpp"
#include "palp/analysis/kf_calibration.hpp"
#include "palp/analysis/second_order.hpp"
#include "palp/probe.hpp"
#include "palp/recording.hpp"

namespace palp {

enum class SweepMethod { stepped, multisine };
const char* sweep_method_name(SweepMethod m);  ///< "stepped", "multisine"

/// contact_stepped: the paper's reference (1.0 A + 0.1 A, 2-20 Hz at 0.05 Hz, settle
/// max(3 cycles, 1.2 s), 5 cycles: ~665 s). contact_multisine: the same peak, 20 s periods,
/// every fourth line (4k+1) across 2-20 Hz, random phases, 1 period dropped + 2 measured: 60 s.
/// free_air: bias at the float current 0.5 A, 0.01 A, 1-10 Hz, multisine.
/// contact_multisine_fast (issue 24, a dynamic map's point): 16 s of program at 1.0 A, omega_n
/// within 0.5 % and zeta within 5 % of the plant's linearisation on palp-sim's 1D objects
/// (resonances 6.7-12.5 Hz) and the pad (19.6-24.6 Hz): 4 s periods (0.25 Hz harmonics; the
/// dropped period is 22 of the slowest contact transient's time constants, 1 / (zeta omega_n) =
/// 0.18 s on the hollow), 1 dropped + 3 measured (the period-to-period sigma);
/// the odd harmonics 9-159 (2.25-39.75 Hz, 76 lines 0.5 Hz apart, 3-4 in the hollow's 1.8 Hz
/// half-power band: from a third of the softest resonance to 1.6 times the stiffest; the empty
/// even lines catch the contact law's even-order distortion);
/// Schroeder phases (crest factor 1.9 against ~2.9 for random ones: 2.6 mA a line instead of 1.7
/// mA at the same peak); true peak 0.03 A, the small-signal level at which the 60 s preset meets
/// the same accuracy (at 0.1 A the contact law's curvature costs 1 % in omega_n, 8 % in zeta).
/// The device plays one amplitude for all lines (LoadMultisine): no per-line shaping.
enum class IdentificationPreset {
  contact_stepped,
  contact_multisine,
  free_air,
  contact_multisine_fast
};

struct IdentificationSettings {
  SweepMethod method = SweepMethod::multisine;
  bool in_contact = true;        ///< contact identification (else free air)
  double bias_A = 1.0;           ///< I_0
  double amplitude_A = 0.1;      ///< peak deviation from the bias (sine amplitude, or the
                                 ///< multisine's true peak)
  double f_lo_Hz = 2.0, f_hi_Hz = 20.0;
  // stepped sine
  double step_Hz = 0.05;
  int settle_cycles = 3;
  double settle_min_s = 1.2;
  int measure_cycles = 5;
  // multisine
  double fundamental_Hz = 0.05;  ///< 1 / period
  int line_step = 4;             ///< excite every line_step-th line (4k+1 with 4)
  int discard_periods = 1;
  int measured_periods = 2;
  std::uint32_t phase_seed = 1;
  proto::PhaseMode phase_mode = proto::PhaseMode::random_seeded;

  double stream_rate_Hz = 1000;  ///< dividing the control rate and the multisine's period
  double settle_s = 1.2;         ///< device time at the bias before the program
  double contact_current_A = 0.5;       ///< I_c
  double max_excursion_m = 3e-3;        ///< free air: refused above this predicted peak
  analysis::FrfOptions frf;             ///< K_f (constant or table)
  analysis::InstrumentDynamics instrument;  ///< for the free-air excursion prediction
  analysis::SecondOrderOptions fit;

  static IdentificationSettings preset(IdentificationPreset p);
  /// Throws ConfigError naming the first bad setting (ranges, band, stream rate); the device-
  /// dependent checks (contact margin, excursion) are check_excitation().
  void validate() const;
  /// The device programs these settings give (the multisine's line amplitude scaled so the
  /// waveform's true peak is amplitude_A at this control rate).
  proto::LoadSweep sweep_program() const;
  proto::LoadMultisine multisine_program(std::uint32_t control_rate_Hz) const;
  /// The excitation's true peak deviation from the bias, A.
  double peak_A(std::uint32_t control_rate_Hz) const;
  /// Device time of the program, s.
  double device_time_s(std::uint32_t control_rate_Hz) const;
  /// Throws ConfigError when the contact margin or the free-air excursion is violated, with the
  /// numbers and what to change ("bias 0.55 A - peak 0.1 A = 0.45 A is below I_c 0.5 A: ...").
  void check_excitation(std::uint32_t control_rate_Hz) const;
  /// Free air: predicted peak excursion over the band, m (|G| max times K_f times the peak).
  double predicted_excursion_m() const;
};

struct IdentifyProgress {
  std::string phase;    ///< "releasing the coil", "floating the coil", "settling", "stepped sine",
                        ///< "multisine", "analysing"
  double fraction = 0;  ///< of the program's device time, 0..1
  double f_Hz = 0;      ///< stepped sine: the line being played
};
using IdentifyProgressFn = std::function<void(const IdentifyProgress&)>;

struct IdentificationRun {
  IdentificationSettings settings;
  std::uint32_t control_rate_Hz = 0;
  /// The program's samples (lab units), sidecar with program, device, calibration and in extra
  /// "identification" (the settings), "stream", "gaps", "samples_missing", "interrupted".
  Recording recording;
  DeviceInfo device;
  ProgramResult program;
  /// The program the device ran (the one of settings.method; the other stays default).
  proto::LoadSweep sweep;
  proto::LoadMultisine multisine;
  bool interrupted = false;
  std::uint64_t samples_missing = 0;
  std::optional<analysis::Frf> frf;
  std::optional<analysis::SecondOrderFit> fit;
  std::string analysis_reason;  ///< why frf/fit are absent
};

IdentificationRun identify(Probe& probe, const IdentificationSettings& settings,
                           const IdentifyProgressFn& progress = {},
                           const std::function<bool()>& cancelled = {});

/// The analysis identify() does, from run.recording (re-analysis of a loaded run): fills frf
/// and fit, or analysis_reason with the text of the DataError that says why the recording gives
/// none; a bad setting (ConfigError) propagates.
void analyze_identification(IdentificationRun& run);

/// A run rebuilt from a loaded recording's sidecar (settings with K_f, the program as the device
/// ran it, the control rate), not yet analysed: call analyze_identification(). ConfigError
/// naming what is missing ("the recording's sidecar has no identification settings
/// (extra.identification): ...") for a recording identify() did not write.
IdentificationRun identification_run_of(const Recording& recording);

/// The settings as the sidecar keeps them (lab units in the key names: mm, N/mm) and back;
/// from_json throws ConfigError naming the first missing or mistyped key.
nlohmann::json identification_settings_json(const IdentificationSettings& s);
IdentificationSettings identification_settings_from_json(const nlohmann::json& j);

/// Force-constant calibration in free air (kf_calibration.hpp): a staircase from start_A to
/// stop_A and back, dwell_s a level; the fit over max_nodes nodes; written to the device's
/// calibration block in RAM (kf table) when `write`, and to flash when `commit`.
struct KfCalibrationSettings {
  double start_A = 0.15, stop_A = 0.62, step_A = 0.01;
  double dwell_s = 1.5;
  double settled_fraction = 0.5;
  std::size_t max_nodes = 16;
  double k_v_N_per_m = 43.9;
  double stream_rate_Hz = 500;
  bool write = true, commit = false;
  /// Free-air balances fix K_f only up to a constant's share (kf_calibration.hpp, KfAnchor):
  /// the fit is anchored at a known K_f, by default the paper's 2.918 N/A at 24 mm of travel
  /// (§II-A); nullopt fits without one (then the result's warning may say it is unreliable).
  std::optional<analysis::KfAnchor> anchor = analysis::KfAnchor{0.024, 2.918};
  void validate() const;
};
struct KfCalibrationRun {
  KfCalibrationSettings settings;
  Recording recording;
  std::vector<analysis::KfStaticPoint> points;
  analysis::KfCalibration calibration;
  bool written = false, committed = false;
  /// Stopped by `cancelled`: the staircase stopped (coil at 0 A), the recording holds what came,
  /// nothing was fitted and nothing written to the device (points and calibration empty).
  bool interrupted = false;
};
/// Runs the K_f calibration (see KfCalibrationSettings); kf_calibration_json
/// (identification_result.hpp) is its result as `palpctl calibrate kf --json` prints it.
KfCalibrationRun calibrate_kf(Probe& probe, const KfCalibrationSettings& settings,
                              const IdentifyProgressFn& progress = {},
                              const std::function<bool()>& cancelled = {});

}  // namespace palp
