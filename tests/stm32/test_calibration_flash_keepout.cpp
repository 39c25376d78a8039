// SPDX-License-Identifier: Apache-2.0
// The flash a host-side firmware update must never erase (proto::board_calibration_flash, used by
// palp::flash, palp/flash.hpp) is exactly where this board keeps its calibration journal
// (flash_driver.hpp): one fact in two places, checked here.
#include <gtest/gtest.h>

#include "calibration_flash.hpp"
#include "palp/protocol/board_id.hpp"

namespace palp::stm32 {
namespace {

TEST(CalibrationFlashKeepout, TheRangeAFirmwareUpdateKeepsIsExactlyTheJournalsTwoPages) {
  constexpr proto::FlashRange keep = proto::board_calibration_flash(proto::BoardId::stm32g474);
  static_assert(keep.begin == flash::kStorageBase && keep.end == flash::kStorageEnd);
  EXPECT_EQ(keep.begin, 0x0807F000u);
  EXPECT_EQ(keep.end - keep.begin, flash::kStoragePages * flash::kPageSize);
  // and the image starts below it, at the flash's first byte
  EXPECT_LT(proto::board_image_address(proto::BoardId::stm32g474), keep.begin);
}

}  // namespace
}  // namespace palp::stm32
