// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the result-directory and trace readers (docs/result-format.md): the input
// as a result directory's result.json read by load_result, and as a trace file read by
// load_trace. Properties:
//  - nothing crashes, reads out of bounds or throws anything but palp::RecordingError (result)
//    or palp::ConfigError (trace);
//  - a refusal's message is one line of printable text (what it quotes is escaped).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_input_file.hpp"
#include "palp/error.hpp"
#include "palp/result.hpp"
#include "palp/trace.hpp"

namespace {

[[noreturn]] void fail() { __builtin_trap(); }

void check_message(const std::string& m) {
  for (const char c : m)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) fail();
}

/// A result directory of this process, with one small valid recording a result.json may list.
const std::filesystem::path& result_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("palp-fuzz-result-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::ofstream(d / "run.csv") << "t_s,i_A,z_mm\n0,0.1,1\n0.001,0.2,1.1\n";
    std::atexit([] { std::filesystem::remove_all(result_dir()); });
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = result_dir();
  {
    std::ofstream out(dir / "result.json", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)palp::load_result(dir);
  } catch (const palp::RecordingError& e) {
    check_message(e.what());
  }
  try {
    (void)palp::load_trace(palp::fuzz::as_file(data, size));
  } catch (const palp::ConfigError& e) {
    check_message(e.what());
  }
  return 0;
}
