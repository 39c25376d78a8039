// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for palp-sim's control channel: each input line (split at '\n', as the
// channel splits its byte stream) through parse_control. Properties:
//  - nothing crashes or reads out of bounds (ASan/UBSan watch);
//  - a refused line always gets a one-line reason; an accepted one none.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "palp/sim/control.hpp"

namespace {
[[noreturn]] void fail() { __builtin_trap(); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  for (;;) {
    const std::size_t nl = rest.find('\n');
    const std::string_view line = rest.substr(0, nl);
    std::string error;
    const auto c = palp::sim::parse_control(line, error);
    if (c.has_value() != error.empty()) fail();
    if (error.find('\n') != std::string::npos) fail();
    if (nl == std::string_view::npos) break;
    rest.remove_prefix(nl + 1);
  }
  return 0;
}
