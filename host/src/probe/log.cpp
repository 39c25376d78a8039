// SPDX-License-Identifier: Apache-2.0
// The SDK's log handler (palp/log.hpp) and the internal call that reports through it.
#include "probe/log.hpp"

#include <memory>
#include <mutex>

namespace palp {
namespace {

std::mutex& handler_mutex() {
  static std::mutex m;
  return m;
}

std::shared_ptr<const LogHandler>& handler_slot() {
  static std::shared_ptr<const LogHandler> h;
  return h;
}

}  // namespace

const char* log_level_name(LogLevel level) {
  switch (level) {
    case LogLevel::info: return "info";
    case LogLevel::warning: return "warning";
    case LogLevel::error: return "error";
  }
  return "?";
}

void set_log_handler(LogHandler handler) {
  auto h = handler ? std::make_shared<const LogHandler>(std::move(handler)) : nullptr;
  std::lock_guard lock(handler_mutex());
  handler_slot() = std::move(h);
}

namespace detail {

bool logging() {
  std::lock_guard lock(handler_mutex());
  return handler_slot() != nullptr;
}

void log(LogLevel level, const std::string& message) {
  std::shared_ptr<const LogHandler> h;
  {
    std::lock_guard lock(handler_mutex());
    h = handler_slot();
  }
  if (!h) return;
  try {
    (*h)(level, message);
  } catch (...) {
    // a handler that throws must not take the SDK's I/O thread down with it
  }
}

}  // namespace detail
}  // namespace palp
