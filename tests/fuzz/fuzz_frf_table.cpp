// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the frequency-response table reader (palp/analysis/frf_table.hpp): the
// input parsed as a table, and looked at by is_frf_table from a file. Properties:
//  - nothing crashes, reads out of bounds or throws anything but palp::RecordingError;
//  - an accepted table has >= 3 lines, f_Hz positive and strictly increasing, finite values;
//  - a refusal's message is one line of printable text (what it quotes is escaped).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input_file.hpp"
#include "palp/analysis/frf_table.hpp"
#include "palp/error.hpp"

namespace {
[[noreturn]] void fail() { __builtin_trap(); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const palp::analysis::Frf f = palp::analysis::parse_frf_table(text, "t.csv");
    if (f.lines.size() < 3) fail();
    for (std::size_t k = 0; k < f.lines.size(); ++k) {
      const auto& l = f.lines[k];
      if (!(l.f_Hz > 0) || !std::isfinite(l.G_m_per_N.real()) || !std::isfinite(l.G_m_per_N.imag()))
        fail();
      if (k > 0 && !(l.f_Hz > f.lines[k - 1].f_Hz)) fail();
    }
  } catch (const palp::RecordingError& e) {
    for (const char c : std::string(e.what()))
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) fail();
  }
  (void)palp::analysis::is_frf_table(palp::fuzz::as_file(data, size));
  return 0;
}
