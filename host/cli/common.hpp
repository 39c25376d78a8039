// SPDX-License-Identifier: Apache-2.0
// palpctl's shared pieces: the global options, the exit codes, the error-to-exit-code mapping,
// lab-unit conversions (the SDK is SI; the CLI prints mm, A, s, Hz, Pa, N/mm), output helpers
// and the Ctrl-C flag.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "palp/analysis/indentation.hpp"
#include "palp/probe.hpp"

namespace palpctl {

using nlohmann::json;

/// The documented exit codes (host/cli/README.md).
enum ExitCode : int {
  kOk = 0,
  kRuntime = 1,     ///< the device refused something, a file could not be written, ...
  kUsage = 2,       ///< bad command line, bad option value, bad URI
  kConnection = 3,  ///< the device could not be reached or the link was lost
  kTimeout = 4,     ///< a reply or the program's end did not come in time
  kVersion = 5,     ///< the handshake said incompatible
  kFault = 6,       ///< the device's fault latch is set (or tripped during the command)
  kInterrupted = 130,  ///< Ctrl-C (what was recorded so far is kept)
};

/// Global options and the chosen command's action.
struct Context {
  std::string uri;
  double timeout_s = 2.0;
  bool json = false;
  std::function<int()> action;

  /// Connects and runs the handshake with the global options (--uri, --timeout-s).
  palp::Probe connect() const { return connect(uri); }
  /// The same at another URI (a rig file's probe_uri).
  palp::Probe connect(const std::string& probe_uri) const;
};

// --- command registration (one file per command group) ------------------------------------
void add_list_command(CLI::App& app, Context& ctx);
void add_info_command(CLI::App& app, Context& ctx);
void add_monitor_command(CLI::App& app, Context& ctx);
void add_stream_command(CLI::App& app, Context& ctx);
void add_run_command(CLI::App& app, Context& ctx);
void add_calibrate_command(CLI::App& app, Context& ctx);
void add_fault_command(CLI::App& app, Context& ctx);
void add_trace_command(CLI::App& app, Context& ctx);  // trace, touch-off
void add_analyze_command(CLI::App& app, Context& ctx);  // analyze indentation|pressure|boyle
void add_indent_command(CLI::App& app, Context& ctx);
void add_map_command(CLI::App& app, Context& ctx);
void add_sweep_commands(CLI::App& app, Context& ctx);  // freeair, sweep
void add_flash_command(CLI::App& app, Context& ctx);
void add_export_command(CLI::App& app, Context& ctx);  // export --format csv
void add_report_command(CLI::App& app, Context& ctx);  // report INPUT --out FILE.html
void add_params_command(CLI::App& app, Context& ctx);  // params get|set|dump|restore
void add_completion_command(CLI::App& app, Context& ctx);  // completion bash|zsh (hidden)
/// analyze sweep | freeair (registered by add_analyze_command).
void add_analyze_sweep_commands(CLI::App* analyze, Context& ctx);
/// palpctl analyze map (registered with the other analyze commands, run by cmd_map.cpp).
int analyze_map_command(const Context& ctx, const std::string& dir,
                        const palp::analysis::IndentationParams& params, bool kf_table, double contrast);

/// Option checks with messages that name the option's value plainly (CLI11's own positive-number
/// check prints its whole double range for a value that is not a number).
extern const CLI::Validator kPositive;
extern const CLI::Validator kNonNegative;
/// Every floating-point option of app and its subcommands refuses NaN and infinities ("--ic-A:
/// 'nan' is not a finite number", exit 2) before any command runs: a range check alone lets NaN
/// through, as every comparison with it is false.
void require_finite_numbers(CLI::App& app);

/// -v/--verbose: the SDK's log (palp/log.hpp: link lost and restored, requests resent, stream
/// gaps, robot reconnects) on stderr, a line each: `palpctl: 2026-11-26T05:40:12.345Z warning: ...`.
/// Stream-gap lines: at most 5 per one-second window; the rest counted in a line "N more stream gap
/// lines suppressed (at most 5 a second)" before the next gap line printed, and at exit.
void log_sdk_to_stderr();

/// Runs a command's action, turning every SDK error into its exit code and a message on stderr
/// (and, with --json, an {"error": ...} object on stdout).
int run_guarded(const Context& ctx, const std::function<int()>& action);

/// Before `map --resume` and `trace --resume`, the state a killed palpctl left: make_safe() stops
/// a program or contact hold still running, and a latched heartbeat_timeout (the device's
/// watchdog tripped because that palpctl stopped sending) is cleared, saying so on stderr: the
/// current is already 0 A and this palpctl's heartbeat runs, so nothing of the instrument is at
/// fault. Any other latched fault stays set, and the resume then exits 6 naming it (its cause
/// needs a person: palpctl fault show, then fault clear).
void recover_for_resume(palp::Probe& probe);

/// Prints a JSON document on stdout (one line per document when `compact`).
void print_json(const json& j, bool compact = false);

// --- Ctrl-C -------------------------------------------------------------------------------
/// Installs the SIGINT/SIGTERM handler; interrupted() turns true once one arrived. Only the
/// commands with a loop that checks it (monitor, stream, run) install it; elsewhere Ctrl-C ends
/// palpctl at once (the device's heartbeat watchdog then zeroes any current).
void catch_interrupts();
bool interrupted();

// --- lab units ----------------------------------------------------------------------------
constexpr double mm_from_m(double m) { return m * 1e3; }
constexpr double mm_from_counts(std::int64_t c) { return static_cast<double>(c) / 1e3; }
std::int32_t counts_from_mm(double mm);
constexpr double s_from_ms(double ms) { return ms / 1e3; }
constexpr double N_per_mm_from_N_per_m(double k) { return k / 1e3; }
/// A protocol f32 as the double with the same shortest decimal form (3.2f prints 3.2, not
/// 3.200000047683716).
double f32(float v);

/// An enum value's catalogue name ("idle", "travel_limit", ...).
template <class E>
std::string name_of(E value) {
  const char* n = palp::proto::enum_name(value);
  return n != nullptr ? n : std::to_string(static_cast<unsigned>(value)) + " (unknown)";
}

// --- the SDK's structs in lab units, as JSON (keys carry their units) ----------------------
json to_json(const palp::Handshake& h);
json to_json(const palp::Params& p);
json to_json(const palp::HealthCounters& h);
json to_json(const palp::Status& s);
json to_json(const palp::FaultInfo& f);
json to_json(const palp::ProgramResult& r);

/// Prints a JSON object as indented "key: value" lines (the human form of the same data).
void print_text(const json& j, int indent = 0);

/// A number as the analyses print it: six significant digits.
std::string fmt(double v);

// --- progress on stderr -------------------------------------------------------------------
/// "\r<label>: 42% (4200/10000 samples)" at most a few times per second; nothing when disabled.
class Progress {
 public:
  /// what: the unit counted ("samples", "points").
  Progress(std::string label, std::uint64_t expected, bool enabled, std::string what = "samples");
  void update(std::uint64_t done);
  void finish(std::uint64_t done);

 private:
  std::string label_;
  std::string what_;
  std::uint64_t expected_;
  bool enabled_;
  bool tty_;
  double last_s_ = -1;
  bool shown_ = false;
};

}  // namespace palpctl
