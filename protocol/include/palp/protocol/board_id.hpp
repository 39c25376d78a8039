// SPDX-License-Identifier: Apache-2.0
// The boards a palp firmware image is built for: one number per board (the image metadata's
// board field, image_metadata.hpp) and its name (the text DeviceInfo.board carries).
//
// Freestanding: builds for the host and for Cortex-M4.
#pragma once

#include <cstdint>

namespace palp::proto {

/// A firmware image's board. Values are frozen once released: add boards, never renumber.
enum class BoardId : std::uint16_t {
  unknown = 0,
  stm32g474 = 1,        ///< the probe controller: STM32G474RE (firmware/board/stm32g474)
  qemu_mps2_an386 = 2,  ///< QEMU's mps2-an386, the controller's stand-in (firmware/board/qemu)
};

/// The board's name: "stm32g474", "qemu-mps2-an386"; "unknown" for any other value.
constexpr const char* board_name(BoardId board) {
  switch (board) {
    case BoardId::stm32g474: return "stm32g474";
    case BoardId::qemu_mps2_an386: return "qemu-mps2-an386";
    case BoardId::unknown: break;
  }
  return "unknown";
}

/// Where the board's images start (byte 0 of the .bin): its flash. 0 for an unknown board.
constexpr std::uint32_t board_image_address(BoardId board) {
  switch (board) {
    case BoardId::stm32g474: return 0x08000000u;  // stm32g474-facts.md §1.1 (stm32g474.ld)
    case BoardId::qemu_mps2_an386: return 0x00000000u;  // the flash alias (mps2_an386.ld)
    case BoardId::unknown: break;
  }
  return 0;
}

/// A range of flash addresses, [begin, end); empty when begin == end.
struct FlashRange {
  std::uint32_t begin = 0, end = 0;
};

/// The flash the board keeps for its calibration journal: a firmware update must never erase it
/// (palp/flash.hpp). stm32g474: bank 2's last two pages, 0x0807F000..0x08080000
/// (firmware/board/stm32g474/flash_driver.hpp: kStorageBase, kStorageEnd; tests/stm32 checks
/// both agree). Empty for a board without one.
constexpr FlashRange board_calibration_flash(BoardId board) {
  switch (board) {
    case BoardId::stm32g474: return {0x0807F000u, 0x08080000u};
    case BoardId::qemu_mps2_an386:
    case BoardId::unknown: break;
  }
  return {};
}

}  // namespace palp::proto
