// SPDX-License-Identifier: Apache-2.0
// What the HDF5 test files share (not a test): a fresh directory per test, the comparison of two
// recordings, and editing a written file with the HDF5 API as damage or a foreign tool would.
#pragma once

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/hdf5.hpp"

namespace palp_test {

namespace fs = std::filesystem;

class Hdf5 : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("palp-hdf5-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  std::string read_error(const fs::path& p) {
    try {
      (void)palp::read_recording_hdf5(p);
    } catch (const palp::RecordingError& e) {
      return e.what();
    }
    return "(no error)";
  }
  fs::path dir_;
};

inline void expect_same(const palp::Recording& a, const palp::Recording& b) {
  EXPECT_EQ(a.t_s, b.t_s);
  EXPECT_EQ(a.i_A, b.i_A);
  EXPECT_EQ(a.z_mm, b.z_mm);
  for (std::size_t k = 0; k < a.z_mm.size() && k < b.z_mm.size(); ++k)
    EXPECT_EQ(std::signbit(a.z_mm[k]), std::signbit(b.z_mm[k])) << k;
  EXPECT_EQ(a.rep, b.rep);
  EXPECT_EQ(a.sample_index, b.sample_index);
  EXPECT_EQ(a.i_cmd_A, b.i_cmd_A);
  EXPECT_EQ(a.p_Pa, b.p_Pa);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.rep_source, b.rep_source);
  EXPECT_EQ(a.ignored_columns, b.ignored_columns);
  ASSERT_EQ(a.sidecar.has_value(), b.sidecar.has_value());
  if (a.sidecar) {
    EXPECT_EQ(palp::sidecar_to_json(*a.sidecar), palp::sidecar_to_json(*b.sidecar));
  }
}

/// Changes a written file with the HDF5 API, as damage or a foreign tool would.
template <class F>
void edit(const fs::path& p, F&& f) {
  const hid_t file = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  f(file);
  H5Fclose(file);
}

}  // namespace palp_test
