// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/control.hpp"

#include "palp/protocol/robot_bridge/codec.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <vector>

namespace palp::sim {

namespace {

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && (line[k] == ' ' || line[k] == '\t' || line[k] == '\r')) ++k;
    std::size_t e = k;
    while (e < line.size() && line[e] != ' ' && line[e] != '\t' && line[e] != '\r') ++e;
    if (e > k) out.push_back(line.substr(k, e - k));
    k = e;
  }
  return out;
}

bool number(std::string_view w, double& out) {
  const char* end = w.data() + w.size();
  const auto r = std::from_chars(w.data(), end, out);
  return r.ec == std::errc{} && r.ptr == end && std::isfinite(out);
}

template <class U>
bool unsigned_number(std::string_view w, U& out, int base = 10) {
  const char* end = w.data() + w.size();
  const auto r = std::from_chars(w.data(), end, out, base);
  return r.ec == std::errc{} && r.ptr == end;
}

// 'word' (GCC 12 warns falsely on "literal" + std::string at -O3, so built by appending)
std::string q(std::string_view w) {
  std::string s;
  s.reserve(w.size() + 2);
  s += '\'';
  s.append(w);
  s += '\'';
  return s;
}

// fault <kind> [argument]: see control.hpp
std::optional<ControlCommand> parse_fault(const std::vector<std::string_view>& w,
                                          std::string& error) {
  using K = cmd::Fault::Kind;
  const char* kinds = "encoder-stuck, encoder-glitch <counts>, adc-stuck, adc-saturate high|low, "
                      "driver, supply-sag <V> or clear";
  if (w.size() < 2) {
    error = std::string("fault: expected ") + kinds;
    return std::nullopt;
  }
  const std::string_view kind = w[1];
  auto fail = [&](const std::string& what) -> std::optional<ControlCommand> {
    error = "fault " + std::string(kind) + ": " + what;
    return std::nullopt;
  };
  const std::size_t args = w.size() - 2;
  const struct { const char* name; K kind; } bare[] = {
      {"encoder-stuck", K::encoder_stuck}, {"adc-stuck", K::adc_stuck},
      {"driver", K::driver}, {"clear", K::clear}};
  for (const auto& b : bare)
    if (kind == b.name) {
      if (args != 0) return fail("expected no arguments");
      return cmd::Fault{b.kind};
    }
  if (kind == "encoder-glitch") {
    if (args != 1) return fail("expected <counts>");
    std::int32_t n = 0;
    const char* end = w[2].data() + w[2].size();
    const auto r = std::from_chars(w[2].data(), end, n);
    if (r.ec != std::errc{} || r.ptr != end || n == 0 || n > 30000 || n < -30000)
      return fail(q(w[2]) + " is not a whole number of counts, nonzero, -30000 to 30000");
    cmd::Fault f{K::encoder_glitch};
    f.counts = n;
    return f;
  }
  if (kind == "adc-saturate") {
    if (args != 1 || (w[2] != "high" && w[2] != "low")) return fail("expected high or low");
    cmd::Fault f{K::adc_saturate};
    f.high = w[2] == "high";
    return f;
  }
  if (kind == "supply-sag") {
    double v = 0;
    if (args != 1) return fail("expected <V>");
    if (!number(w[2], v) || v < 0) return fail(q(w[2]) + " is not a voltage in V >= 0");
    cmd::Fault f{K::supply_sag};
    f.volts = v;
    return f;
  }
  error = "fault: unknown fault " + q(kind) + "; expected " + kinds;
  return std::nullopt;
}

}  // namespace

const char* control_help() {
  return "help | status | mount <x_mm> <y_mm> <z_mm> | phantom <name>|none | seed <n> | "
         "pace realtime|fast|<factor> | drop-frames <n> | corrupt-frames <n> | "
         "announce <major>.<minor> [0x<hash>] | announce actual | reaction-latency <ms> | "
         "hold-timeout <ms> | robot-reply-delay <ms> | robot-drop | "
         "robot-freeze-heartbeat on|off | robot-reject <result-name> <n> | robot-fault | "
         "fault encoder-stuck | fault encoder-glitch <counts> | fault adc-stuck | "
         "fault adc-saturate high|low | fault driver | fault supply-sag <V> | fault clear";
}

std::optional<ControlCommand> parse_control(std::string_view line, std::string& error) {
  const std::vector<std::string_view> w = words(line);
  if (w.empty()) {
    error = "empty command; try 'help'";
    return std::nullopt;
  }
  const std::string name(w[0]);
  auto bad = [&](const std::string& what) -> std::optional<ControlCommand> {
    error = name + ": " + what;
    return std::nullopt;
  };
  auto arity = [&](std::size_t n, const char* usage) {
    if (w.size() - 1 == n) return true;
    error = name + ": expected " + usage;
    return false;
  };
  auto nonneg_ms = [&](double& v) -> bool {
    if (!arity(1, "<ms>")) return false;
    if (!number(w[1], v) || v < 0) {
      error = name + ": " + q(w[1]) + " is not a duration in ms >= 0";
      return false;
    }
    return true;
  };

  if (name == "help") return arity(0, "no arguments") ? std::optional<ControlCommand>(cmd::Help{}) : std::nullopt;
  if (name == "status") return arity(0, "no arguments") ? std::optional<ControlCommand>(cmd::Status{}) : std::nullopt;
  if (name == "mount") {
    if (!arity(3, "<x_mm> <y_mm> <z_mm>")) return std::nullopt;
    double v[3];
    for (int k = 0; k < 3; ++k)
      if (!number(w[1 + k], v[k])) return bad(q(w[1 + k]) + " is not a number of mm");
    return cmd::Mount{v[0], v[1], v[2]};
  }
  if (name == "phantom") {
    if (!arity(1, "<name> or none")) return std::nullopt;
    for (char c : w[1])
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
        return bad(q(w[1]) + " is not a phantom name (letters, digits, _ and -)");
    return cmd::Phantom{std::string(w[1])};
  }
  if (name == "seed") {
    std::uint64_t s = 0;
    if (!arity(1, "<n>")) return std::nullopt;
    if (!unsigned_number(w[1], s)) return bad(q(w[1]) + " is not an unsigned integer");
    return cmd::Seed{s};
  }
  if (name == "pace") {
    if (!arity(1, "realtime, fast or a factor")) return std::nullopt;
    if (w[1] == "realtime") return cmd::Pace{1.0};
    if (w[1] == "fast") return cmd::Pace{0.0};
    double f = 0;
    if (!number(w[1], f) || f <= 0) return bad(q(w[1]) + " is not realtime, fast or a factor > 0");
    return cmd::Pace{f};
  }
  if (name == "drop-frames" || name == "corrupt-frames") {
    std::uint32_t n = 0;
    if (!arity(1, "<n> (every n-th frame, 0 for none)")) return std::nullopt;
    if (!unsigned_number(w[1], n)) return bad(q(w[1]) + " is not an unsigned integer");
    if (name == "drop-frames") return cmd::DropFrames{n};
    return cmd::CorruptFrames{n};
  }
  if (name == "announce") {
    if (w.size() == 2 && w[1] == "actual") return cmd::Announce{true, 0, 0, std::nullopt};
    if (w.size() != 2 && w.size() != 3) {
      error = "announce: expected <major>.<minor> [0x<hash>] or actual";
      return std::nullopt;
    }
    const std::size_t dot = w[1].find('.');
    unsigned major = 0, minor = 0;
    if (dot == std::string_view::npos || !unsigned_number(w[1].substr(0, dot), major) ||
        !unsigned_number(w[1].substr(dot + 1), minor) || major > 255 || minor > 255)
      return bad(q(w[1]) + " is not a version <major>.<minor> (0-255 each)");
    cmd::Announce a{false, static_cast<std::uint8_t>(major), static_cast<std::uint8_t>(minor),
                    std::nullopt};
    if (w.size() == 3) {
      std::uint32_t h = 0;
      if (w[2].size() < 3 || w[2].substr(0, 2) != "0x" || !unsigned_number(w[2].substr(2), h, 16))
        return bad(q(w[2]) + " is not a schema hash 0x<hex, 32 bits>");
      a.hash = h;
    }
    return a;
  }
  if (name == "reaction-latency") {
    double ms = 0;
    if (!nonneg_ms(ms)) return std::nullopt;
    return cmd::ReactionLatency{ms};
  }
  if (name == "hold-timeout") {
    double ms = 0;
    if (!nonneg_ms(ms)) return std::nullopt;
    return cmd::HoldTimeout{ms};
  }
  if (name == "robot-reply-delay") {
    double ms = 0;
    if (!nonneg_ms(ms)) return std::nullopt;
    return cmd::RobotReplyDelay{ms};
  }
  if (name == "robot-drop") return arity(0, "no arguments") ? std::optional<ControlCommand>(cmd::RobotDrop{}) : std::nullopt;
  if (name == "robot-fault") return arity(0, "no arguments") ? std::optional<ControlCommand>(cmd::RobotFault{}) : std::nullopt;
  if (name == "robot-freeze-heartbeat") {
    if (!arity(1, "on or off")) return std::nullopt;
    if (w[1] == "on") return cmd::RobotFreezeHeartbeat{true};
    if (w[1] == "off") return cmd::RobotFreezeHeartbeat{false};
    return bad(q(w[1]) + " is not on or off");
  }
  if (name == "robot-reject") {
    if (!arity(2, "<result-name> <n>")) return std::nullopt;
    std::uint16_t value = 0;
    bool found = false;
    for (const auto& v : proto::rb::EnumInfo<proto::rb::Result>::values)
      if (w[1] == v.name && v.value >= 32) value = v.value, found = true;
    if (!found) return bad(q(w[1]) + " is not a rejection result (rejected_busy, rejected_not_ready, ...)");
    std::uint32_t n = 0;
    if (!unsigned_number(w[2], n)) return bad(q(w[2]) + " is not an unsigned integer");
    return cmd::RobotReject{value, n};
  }
  if (name == "fault") return parse_fault(w, error);
  error = "unknown command " + q(name) + "; try 'help'";
  return std::nullopt;
}

}  // namespace palp::sim
