// SPDX-License-Identifier: Apache-2.0
// palp_fuzz_seeds: seed corpora for the fuzz targets from the repository's own files, so the
// seeds follow the formats as the docs and vectors do (they cannot drift).
//   palp_fuzz_seeds docs OUT FILE.md...      every fenced code block of each file, one file each
//   palp_fuzz_seeds registers OUT VECTORS    every `regs` line of protocol/vectors/robot_bridge.txt
//                                            as big-endian 16-bit registers, one file each
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

bool write(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
  return static_cast<bool>(out);
}

int docs(const fs::path& out, int argc, char** argv) {
  int written = 0;
  for (int a = 3; a < argc; ++a) {
    std::ifstream in(argv[a], std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "palp_fuzz_seeds: cannot read %s\n", argv[a]);
      return 1;
    }
    std::string line, block;
    bool inside = false;
    int k = 0;
    while (std::getline(in, line)) {
      if (line.starts_with("```")) {
        if (inside && !write(out / (fs::path(argv[a]).stem().string() + "-" +
                                    std::to_string(k++) + ".txt"),
                             block))
          return 1;
        written += inside ? 1 : 0;
        inside = !inside;
        block.clear();
      } else if (inside) {
        block += line + "\n";
      }
    }
  }
  std::printf("wrote %d seeds from fenced blocks into %s\n", written, out.c_str());
  return 0;
}

int registers(const fs::path& out, const char* vectors) {
  std::ifstream in(vectors, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "palp_fuzz_seeds: cannot read %s\n", vectors);
    return 1;
  }
  std::string line;
  int written = 0;
  while (std::getline(in, line)) {
    if (!line.starts_with("regs ")) continue;
    std::istringstream words(line.substr(5));
    std::string bytes, word;
    while (words >> word) {
      const unsigned long v = std::stoul(word, nullptr, 16);
      bytes += static_cast<char>(v >> 8);
      bytes += static_cast<char>(v & 0xFF);
    }
    if (!write(out / ("regs-" + std::to_string(written++) + ".bin"), bytes)) return 1;
  }
  std::printf("wrote %d register seeds into %s\n", written, out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 2 ? argv[1] : "";
  if (mode == "docs") return docs(argv[2], argc, argv);
  if (mode == "registers" && argc == 4) return registers(argv[2], argv[3]);
  std::fprintf(stderr,
               "usage: palp_fuzz_seeds docs OUT FILE.md... | palp_fuzz_seeds registers OUT VECTORS\n");
  return 2;
}
