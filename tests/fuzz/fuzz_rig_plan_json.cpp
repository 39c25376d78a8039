// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the rig and plan file readers (docs/rig-and-plan.md): the input parsed as
// a rig and as a plan, and read from a file as both (the bounded read). Properties:
//  - nothing crashes, reads out of bounds or throws anything but palp::ConfigError;
//  - an accepted plan's every grid point is finite;
//  - a refusal's message is one line of printable text (what it quotes is escaped).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input_file.hpp"
#include "palp/error.hpp"
#include "palp/rig.hpp"

namespace {

[[noreturn]] void fail() { __builtin_trap(); }

template <class F>
void refused_or_ok(F&& f) {
  try {
    f();
  } catch (const palp::ConfigError& e) {
    for (const char c : std::string(e.what()))
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) fail();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  refused_or_ok([&] { (void)palp::parse_rig(text, "rig.json"); });
  refused_or_ok([&] {
    const palp::Plan p = palp::parse_plan(text, "plan.json");
    if (p.grid.rows > 0 && p.grid.columns > 0) {
      for (int r : {0, p.grid.rows - 1})
        for (int c : {0, p.grid.columns - 1}) {
          const auto pt = p.point_m(r, c);
          if (!std::isfinite(pt.first) || !std::isfinite(pt.second)) fail();
        }
    }
  });
  const std::string path = palp::fuzz::as_file(data, size);
  refused_or_ok([&] { (void)palp::load_rig(path); });
  return 0;
}
