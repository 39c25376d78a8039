// SPDX-License-Identifier: Apache-2.0
// palpctl: exit codes, error mapping, lab-unit JSON of the SDK's structs, progress, Ctrl-C.
#include "common.hpp"
#include "gap_lines.hpp"

#include "palp/result.hpp"

#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>

#include "palp/log.hpp"

namespace palpctl {

std::string fmt(double v) {
  std::ostringstream o;
  o.precision(6);
  o << v;
  return o.str();
}

namespace {
volatile std::sig_atomic_t g_interrupted = 0;
void on_interrupt(int) { g_interrupted = 1; }

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int report(const Context& ctx, int code, const char* kind, const std::string& message) {
  std::cerr << "palpctl: " << message << '\n';
  if (ctx.json)
    print_json({{"error", {{"kind", kind}, {"message", message}, {"exit_code", code}}}});
  return code;
}
}  // namespace

palp::Probe Context::connect(const std::string& probe_uri) const {
  palp::ConnectOptions o;
  o.timeout = std::chrono::milliseconds(static_cast<long>(std::lround(timeout_s * 1e3)));
  o.host_software = std::string("palpctl ") + palp::sdk_version();
  return palp::Probe(probe_uri, o);
}

namespace {
CLI::Validator number_check(bool allow_zero) {
  return CLI::Validator(
      [allow_zero](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end == nullptr || *end != '\0' || !std::isfinite(v))
          return "'" + text + "' is not a number";
        if (allow_zero ? v < 0 : v <= 0)
          return "'" + text + "' must be " + (allow_zero ? "0 or more" : "above 0");
        return {};
      },
      allow_zero ? "NONNEGATIVE" : "POSITIVE");
}
}  // namespace

const CLI::Validator kPositive = number_check(false);
const CLI::Validator kNonNegative = number_check(true);

void require_finite_numbers(CLI::App& app) {
  // no name: the option's --help type stays as it was ("FLOAT:FLOAT in [-4 - 4]")
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (!text.empty() && end != nullptr && *end == '\0' && !std::isfinite(v))
          return "'" + text + "' is not a finite number";
        return {};  // a finite number, or text CLI11's own conversion refuses
      },
      "");
  for (CLI::Option* opt : app.get_options())
    if (opt->get_type_name().rfind("FLOAT", 0) == 0) opt->check(finite);
  for (CLI::App* sub : app.get_subcommands({})) require_finite_numbers(*sub);
}

namespace {

/// -v's stream-gap lines: at most kGapLinesPerSecond a second (gap_lines.hpp).
constexpr int kGapLinesPerSecond = 5;

struct GapLines {
  std::mutex mu;
  GapLineLimiter limiter{kGapLinesPerSecond, std::chrono::seconds(1)};
};
GapLines& gap_lines() {
  static auto* g = new GapLines;  // never destroyed: an SDK thread may log during exit
  return *g;
}

std::string log_line(const char* level, const std::string& message) {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&t, &utc);
  char stamp[64];
  std::snprintf(stamp, sizeof stamp, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                static_cast<int>(ms));
  return std::string("palpctl: ") + stamp + " " + level + ": " + message + "\n";
}

std::string suppressed_line(std::uint64_t n) {
  return log_line("warning", std::to_string(n) + " more stream gap line" + (n == 1 ? "" : "s") +
                                 " suppressed (at most " + std::to_string(kGapLinesPerSecond) +
                                 " a second)");
}

}  // namespace

void log_sdk_to_stderr() {
  palp::set_log_handler([](palp::LogLevel level, const std::string& message) {
    std::string text = log_line(palp::log_level_name(level), message);
    if (message.rfind("stream gap:", 0) == 0) {
      GapLines& g = gap_lines();
      std::lock_guard lock(g.mu);
      const auto suppressed = g.limiter.admit(std::chrono::steady_clock::now());
      if (!suppressed) return;
      if (*suppressed > 0) text = suppressed_line(*suppressed) + text;
    }
    // one write per line: lines from the SDK's threads do not interleave
    std::fwrite(text.data(), 1, text.size(), stderr);
  });
  static bool registered = false;
  if (!registered) {
    registered = true;
    std::atexit([] {  // the gap lines suppressed since the last one printed
      GapLines& g = gap_lines();
      std::lock_guard lock(g.mu);
      const std::uint64_t n = g.limiter.take_suppressed();
      if (n == 0) return;
      const std::string text = suppressed_line(n);
      std::fwrite(text.data(), 1, text.size(), stderr);
    });
  }
}

int run_guarded(const Context& ctx, const std::function<int()>& action) {
  try {
    return action();
  } catch (const palp::ConfigError& e) {
    return report(ctx, kUsage, "config", e.what());
  } catch (const palp::ConnectionError& e) {
    return report(ctx, kConnection, "connection", e.what());
  } catch (const palp::TimeoutError& e) {
    return report(ctx, kTimeout, "timeout", e.what());
  } catch (const palp::VersionError& e) {
    return report(ctx, kVersion, "version", e.what());
  } catch (const palp::FaultError& e) {
    return report(ctx, kFault, "fault", e.what());
  } catch (const palp::DeviceError& e) {
    const bool faulted = e.code() == static_cast<std::uint16_t>(palp::proto::ErrorCode::faulted) ||
                         e.code() == static_cast<std::uint16_t>(palp::proto::ErrorCode::fault_persists);
    return report(ctx, faulted ? kFault : kRuntime, faulted ? "fault" : "device", e.what());
  } catch (const palp::Error& e) {
    return report(ctx, kRuntime, "error", e.what());
  } catch (const std::exception& e) {
    return report(ctx, kRuntime, "error", e.what());
  }
}

void recover_for_resume(palp::Probe& probe) {
  const palp::Status st = probe.make_safe();
  if (st.fault != palp::proto::FaultReason::heartbeat_timeout) return;
  probe.clear_fault();
  std::cerr << "palpctl: cleared the latched heartbeat_timeout fault: the device's watchdog tripped "
               "because the previous host stopped sending (it crashed or was killed); the coil is "
               "at 0 A and no program runs, so the resume goes on\n";
}

void print_json(const json& j, bool compact) {
  std::cout << (compact ? j.dump() : j.dump(2)) << '\n' << std::flush;
}

void catch_interrupts() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}
bool interrupted() { return g_interrupted != 0; }

double f32(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf - 1, v);
  *r.ptr = '\0';
  return std::strtod(buf, nullptr);
}

std::int32_t counts_from_mm(double mm) { return static_cast<std::int32_t>(std::lround(mm * 1e3)); }

json to_json(const palp::Handshake& h) {
  return {{"verdict", h.missing_features ? "compatible_missing_features" : "compatible"},
          {"missing", h.missing},
          {"message", h.message}};
}

json to_json(const palp::Params& p) { return palp::params_json(p); }

json to_json(const palp::HealthCounters& h) { return palp::health_json(h); }

json to_json(const palp::Status& s) {
  return {{"t_device_s", s.t_device_s},
          {"state", name_of(s.state)},
          {"fault", name_of(s.fault)},
          {"program", name_of(s.program)},
          {"program_state", name_of(s.program_state)},
          {"i_cmd_A", s.i_cmd_A},
          {"i_A", s.i_A},
          {"z_mm", mm_from_m(s.z_m)},
          {"i2t_fraction", s.i2t_fraction},
          {"streaming", s.streaming},
          {"status_bits", s.status_bits}};
}

json to_json(const palp::FaultInfo& f) { return palp::fault_json(f); }

json to_json(const palp::ProgramResult& r) { return palp::program_result_json(r); }

void print_text(const json& j, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it->is_object()) {
      std::cout << pad << it.key() << ":\n";
      print_text(*it, indent + 2);
    } else if (it->is_array() && !it->empty() && it->front().is_object()) {
      std::cout << pad << it.key() << ":\n";
      for (const auto& e : *it) std::cout << pad << "  - " << e.dump() << '\n';
    } else if (it->is_string()) {
      std::cout << pad << it.key() << ": " << it->get<std::string>() << '\n';
    } else {
      std::cout << pad << it.key() << ": " << it->dump() << '\n';
    }
  }
}

Progress::Progress(std::string label, std::uint64_t expected, bool enabled, std::string what)
    : label_(std::move(label)), what_(std::move(what)), expected_(expected), enabled_(enabled),
      tty_(::isatty(2) != 0) {}

void Progress::update(std::uint64_t done) {
  if (!enabled_) return;
  const double t = now_s();
  // on a terminal one line rewritten 4 times a second; into a file or pipe a line a second
  if (last_s_ >= 0 && t - last_s_ < (tty_ ? 0.25 : 1.0)) return;
  last_s_ = t;
  shown_ = true;
  const double pct = expected_ > 0 ? std::min(100.0, 100.0 * static_cast<double>(done) /
                                                         static_cast<double>(expected_))
                                   : 0.0;
  std::fprintf(stderr, "%s%s: %3.0f%% (%llu/%llu %s)%s", tty_ ? "\r" : "", label_.c_str(), pct,
               static_cast<unsigned long long>(done), static_cast<unsigned long long>(expected_),
               what_.c_str(), tty_ ? "" : "\n");
  std::fflush(stderr);
}

void Progress::finish(std::uint64_t done) {
  if (!enabled_) return;
  last_s_ = -1;
  update(done);
  if (shown_ && tty_) std::fputc('\n', stderr);
}

}  // namespace palpctl
