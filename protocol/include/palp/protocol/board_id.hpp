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

}  // namespace palp::proto
