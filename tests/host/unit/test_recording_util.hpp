// SPDX-License-Identifier: Apache-2.0
// Helpers for the recording tests: a fresh directory per test, whole-file text, the exact
// RecordingError check, and a staircase current whose repetition starts are known.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "palp/error.hpp"

namespace palp_test {

namespace fs = std::filesystem;

/// A directory of its own for the running test, removed with everything in it afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("palp-recording-" + std::to_string(::getpid()) + "-" +
                                         info->test_suite_name() + "." + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  /// The names of every file in the directory, hidden ones included, sorted.
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

inline void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Expects f() to throw a RecordingError for `file` with exactly this line and problem.
template <class F>
void expect_recording_error(F&& f, const fs::path& file, std::size_t line,
                            const std::string& problem) {
  try {
    f();
    ADD_FAILURE() << "no RecordingError; expected line " << line << ": " << problem;
  } catch (const palp::RecordingError& e) {
    EXPECT_EQ(e.problem(), problem);
    EXPECT_EQ(e.line(), line);
    EXPECT_EQ(e.file(), file.string());
    EXPECT_EQ(std::string(e.what()),
              file.string() + (line > 0 ? ":" + std::to_string(line) : "") + ": " + problem);
  }
}

/// The paper's staircase: 0.5 A → 3 A in steps of step_A, then the symmetric unload back to
/// 0.5 A, each level held samples_per_step samples, `reps` times, plus white noise of noise_A
/// rms (seeded). starts receives the first sample of every repetition.
inline std::vector<double> staircase(double step_A, int samples_per_step, int reps, double noise_A,
                                     std::vector<std::size_t>& starts, unsigned seed = 7) {
  const int up_levels = static_cast<int>(std::lround(2.5 / step_A)) + 1;
  std::vector<double> levels;
  for (int k = 0; k < up_levels; ++k) levels.push_back(0.5 + k * step_A);
  for (int k = up_levels - 2; k >= 0; --k) levels.push_back(0.5 + k * step_A);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_A);
  std::vector<double> i_A;
  starts.clear();
  for (int r = 0; r < reps; ++r) {
    starts.push_back(i_A.size());
    for (const double level : levels)
      for (int s = 0; s < samples_per_step; ++s)
        i_A.push_back(level + (noise_A > 0 ? noise(rng) : 0.0));
  }
  return i_A;
}

}  // namespace palp_test
