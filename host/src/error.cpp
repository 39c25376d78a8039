// SPDX-License-Identifier: Apache-2.0
#include "palp/error.hpp"

#include <cstdio>

namespace palp {
namespace {
std::string timeout_text(const std::string& what, double timeout_s,
                         const std::optional<HealthCounters>& h) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g s", timeout_s);
  std::string s = "timed out after " + std::string(buf) + " waiting for " + what;
  s += h ? "; health: " + describe(*h) : "; no health counters read yet";
  return s;
}
}  // namespace

TimeoutError::TimeoutError(const std::string& what, double timeout_s,
                           std::optional<HealthCounters> health)
    : Error(timeout_text(what, timeout_s, health)), waited_for_(what), timeout_s_(timeout_s),
      health_(std::move(health)) {}

DeviceError::DeviceError(const std::string& message, std::string request, std::uint16_t code,
                         std::uint8_t field_index, std::int32_t detail)
    : Error(message), request_(std::move(request)), code_(code), field_index_(field_index),
      detail_(detail) {}

RecordingError::RecordingError(const std::string& file, std::size_t line,
                               const std::string& problem)
    : Error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + problem),
      file_(file), line_(line), problem_(problem) {}

}  // namespace palp
