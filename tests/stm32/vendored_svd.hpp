// SPDX-License-Identifier: Apache-2.0
// The vendored SVD (firmware/board/stm32g474/svd/STM32G474.svd.xz), read and parsed once per test
// program; a read or parse failure fails the calling test with the reader's error.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "svd_reader.hpp"

namespace palp::stm32 {

inline const svd::Device& vendored_svd() {
  static const svd::Device device = [] {
    std::string error;
    const std::string xml = svd::read_xz(PALP_STM32G474_SVD, error);
    EXPECT_TRUE(error.empty()) << error;
    auto parsed = svd::parse(xml, error);
    EXPECT_TRUE(parsed.has_value()) << error;
    return parsed.value_or(svd::Device{});
  }();
  return device;
}

}  // namespace palp::stm32
