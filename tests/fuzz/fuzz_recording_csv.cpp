// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the recording CSV reader (docs/recording-format.md): the input as a
// run.csv read by read_recording (without a sidecar) and by recording_row_lines. Properties:
//  - nothing crashes, reads out of bounds or throws anything but palp::RecordingError;
//  - an accepted file has as many data rows as recording_row_lines finds lines, every column
//    as long as t_s, t_s never decreasing, no NaN or infinity read;
//  - a refusal's message is one line of printable text (what it quotes is escaped).
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.hpp"
#include "palp/error.hpp"
#include "palp/recording.hpp"

namespace {

[[noreturn]] void fail() { __builtin_trap(); }

void check_message(const std::string& m) {
  for (const char c : m)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) fail();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = palp::fuzz::as_file(data, size);
  try {
    const palp::Recording r = palp::read_recording(path, palp::ReadOptions{.read_sidecar = false});
    const std::size_t n = r.size();
    if (n == 0 || r.i_A.size() != n || r.z_mm.size() != n || r.rep.size() != n) fail();
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isfinite(r.t_s[k]) || !std::isfinite(r.i_A[k]) || !std::isfinite(r.z_mm[k])) fail();
      if (k > 0 && r.t_s[k] < r.t_s[k - 1]) fail();
    }
    if (palp::recording_row_lines(path).size() != n) fail();
  } catch (const palp::RecordingError& e) {
    check_message(e.what());
  }
  return 0;
}
