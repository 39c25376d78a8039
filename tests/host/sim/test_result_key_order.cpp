// SPDX-License-Identifier: Apache-2.0
// result.json's top-level keys come in the order docs/result-format.md's table lists them: an
// indentation result written by palp::write_result (no device needed: a recording of three rows,
// not analysed) read back keeping its key order, against the doc's table.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "json_keys.hpp"
#include "palp/result.hpp"

namespace {

namespace fs = std::filesystem;

/// The first-column keys of the table under "### result.json" in docs/result-format.md.
std::vector<std::string> documented_keys() {
  std::ifstream in(std::string(PALP_SOURCE_DIR) + "/docs/result-format.md");
  std::vector<std::string> keys;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("### ", 0) == 0) {
      if (inside) break;
      inside = line == "### result.json";
    } else if (inside && line.rfind("| `", 0) == 0) {
      keys.push_back(line.substr(3, line.find('`', 3) - 3));
    }
  }
  return keys;
}

TEST(ResultKeyOrder, ResultJsonTopLevelKeysFollowTheOrderOfTheResultFormatDoc) {
  palp::IndentationRun run;
  for (int k = 0; k < 3; ++k)
    run.recording.append({.sample_index = static_cast<std::uint64_t>(k), .t_s = 0.001 * k, .i_A = 0.5,
                          .z_mm = 1.0});
  run.analysis_reason = "a test";
  run.pressure_reason = "a test";
  const fs::path dir = fs::temp_directory_path() / ("palp-key-order-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  palp::write_result(dir, run);
  const auto doc = palp::test::read_ordered_json((dir / "result.json").string());
  fs::remove_all(dir);

  std::vector<std::string> written;  // the top level, without the <key>_reason companions
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (it.key().size() < 7 || it.key().substr(it.key().size() - 7) != "_reason") written.push_back(it.key());
  const auto documented = documented_keys();
  ASSERT_EQ(documented.size(), 11u) << "the doc's table was not found";
  EXPECT_EQ(written, documented);
  EXPECT_EQ(std::next(doc.begin(), 10).key(), "analysis_reason") << "a reason follows its key";
}

}  // namespace
