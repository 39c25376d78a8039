// SPDX-License-Identifier: Apache-2.0
// What the experiments (indent(), identify(), calibrate_kf()) share: releasing the coil, recording
// the samples a device program drives, and the sidecar's common part (device, calibration, stroke origin, stream).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "format/field_table.hpp"
#include "palp/probe.hpp"
#include "palp/recording.hpp"

namespace palp::experiment {

inline constexpr double kCountM = 1e-6;            ///< one encoder count, m (SPEC: 1 µm)
inline constexpr double kMaxStreamRate_Hz = 1000;  ///< the experiments stream at <= 1 kHz
inline constexpr std::uint32_t kFloatCounts = 500; ///< the coil has left its rear stop (0.5 mm)

using format::f32;  ///< the shortest decimal of a protocol f32 as a double (0.01f reads 0.01)

/// Runs body() and returns what it returns; when it throws, first puts the probe in its safe
/// state (Probe::make_safe: no program, no contact hold, 0 A, stream stopped; its own errors
/// ignored, the heartbeat watchdog is the last resort), then rethrows. Every experiment's entry
/// point runs under it, so no error path leaves the coil driven.
template <class F>
decltype(auto) or_make_safe(Probe& probe, F&& body) {
  try {
    return body();
  } catch (...) {
    try {
      probe.make_safe();
    } catch (...) {
    }
    throw;
  }
}

/// Waits until the device clock reaches until_s (or cancelled()).
void wait_device_time(Probe& probe, double until_s, const std::function<bool()>& cancelled);

/// Stops a program left running or a contact hold carrying current and waits settle_s of device
/// time; returns whether it had to. Calls announce() first when it does.
bool release_coil(Probe& probe, double settle_s, const std::function<bool()>& cancelled,
                  const std::function<void()>& announce);

/// Floats the coil off its rear stop: a contact watch holding current_A that fires after
/// kFloatCounts of travel (a fired watch keeps its current on). Returns the event; throws
/// TimeoutError after 10 s, the message ending with `hint` (why the coil may not have moved).
ContactEvent float_coil(Probe& probe, double current_A, const std::string& hint);

/// What record_program() collected.
struct ProgramRecording {
  Recording recording;  ///< the samples the program drove (status program_running), lab units
  nlohmann::json gaps = nlohmann::json::array();
  std::uint64_t samples_missing = 0;
  ProgramResult program;
  bool interrupted = false;
};

/// With the stream configured: starts it, calls load_and_start() (load + start the program),
/// records every sample the program drives until it ends (waiting up to 2 x expected_s + 30 s),
/// reporting progress(elapsed device time of the program, last sample) about every 200 ms; on
/// cancelled() stops the program and returns what came (interrupted). Always leaves the coil at
/// 0 A and the stream stopped; rethrows the first error after that.
ProgramRecording record_program(Probe& probe, const std::function<void()>& load_and_start,
                                double expected_s,
                                const std::function<void(double, const Sample&)>& progress,
                                const std::function<bool()>& cancelled);

/// The key of a tangent depth in the summary's k_at_depth_N_per_mm ("1_mm", "0.5_mm": the depth
/// in mm to the nearest nm, shortest decimal). result.json and the tidy CSV (tidy_csv.hpp) name
/// depths with it.
std::string depth_key(double depth_m);

/// A PhaseMode by its catalogue name; ConfigError "where: unknown phase_mode ..." else.
proto::PhaseMode phase_mode_named(const std::string& name, const std::string& where);

/// The sidecar's common part: setup_sidecar (result.hpp: device with uri, calibration, stroke
/// origin or why not, zeroing, sdk version, "stream") and in extra "experiment", "gaps",
/// "samples_missing", "interrupted".
Sidecar base_sidecar(Probe& probe, const std::string& experiment, const ProgramRecording& r);

}  // namespace palp::experiment
