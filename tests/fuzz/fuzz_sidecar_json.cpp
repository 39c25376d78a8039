// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the recording sidecar reader (docs/recording-format.md): the input as a
// run.json read by read_sidecar. Properties:
//  - nothing crashes, reads out of bounds or throws anything but palp::RecordingError;
//  - an accepted sidecar writes (sidecar_to_json) and reads back to the same JSON;
//  - a refusal's message is one line of printable text (what it quotes is escaped).
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.hpp"
#include "palp/error.hpp"
#include "palp/recording.hpp"

namespace {
[[noreturn]] void fail() { __builtin_trap(); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  palp::Sidecar s;
  try {
    s = palp::read_sidecar(palp::fuzz::as_file(data, size));
  } catch (const palp::RecordingError& e) {
    for (const char c : std::string(e.what()))
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) fail();
    return 0;
  }
  const nlohmann::json written = palp::sidecar_to_json(s);  // throws (a finding) if it cannot
  if (palp::sidecar_to_json(palp::sidecar_from_json(written)) != written) fail();
  return 0;
}
