// SPDX-License-Identifier: Apache-2.0
// The shipped phantoms are built into palp_plant as text (so an installed library needs no path
// to them): the text is each file's, byte for byte, every file is there, and another name is
// refused naming the shipped ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "palp/plant/phantom.hpp"

namespace palp::plant {
namespace {

namespace fs = std::filesystem;

TEST(ShippedPhantoms, EachIsItsFileByteForByteAndEveryFileIsShipped) {
  const fs::path dir = fs::path(PALP_SOURCE_DIR) / "hil" / "plant" / "phantoms";
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".phantom") files.push_back(e.path().stem().string());
  std::sort(files.begin(), files.end());
  std::vector<std::string> names;
  for (const std::string_view n : shipped_phantom_names()) names.emplace_back(n);
  EXPECT_EQ(names, files);
  for (const std::string& name : files) {
    std::ifstream in(dir / (name + ".phantom"), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(shipped_phantom_text(name), text.str()) << name;
  }
  EXPECT_EQ(load_shipped_phantom("pad_2d")->name(), load_phantom(dir / "pad_2d.phantom")->name());
}

TEST(ShippedPhantoms, AnotherNameIsRefusedNamingTheShippedOnes) {
  try {
    load_shipped_phantom("soft_1d");
    FAIL() << "no error";
  } catch (const PhantomError& e) {
    EXPECT_STREQ(e.what(),
                 "no shipped phantom \"soft_1d\" (the shipped ones: hollow_1d, insert_1d, pad_2d, "
                 "pad_2d_damping, pad_2d_steep, plane_tilted_10, solid_1d, wedge_0, wedge_25)");
  }
}

}  // namespace
}  // namespace palp::plant
