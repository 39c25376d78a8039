// SPDX-License-Identifier: Apache-2.0
// A file of the source tree (PALP_SOURCE_DIR) as bytes, for tests that check code against the
// documents it implements. An unreadable file fails the calling test and returns "".
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace palp::test {

inline std::string read_source(const std::string& relative) {
  std::ifstream in(std::string(PALP_SOURCE_DIR) + "/" + relative, std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot read " << relative;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace palp::test
