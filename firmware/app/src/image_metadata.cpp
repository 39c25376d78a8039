// SPDX-License-Identifier: Apache-2.0
// The image's metadata block (protocol/include/palp/protocol/image_metadata.hpp), placed in
// section .palp_metadata, which the board's linker script puts at kImageMetadataOffset. Built
// into an image by palp_image_metadata() (firmware/CMakeLists.txt), which names the board
// (PALP_IMAGE_BOARD, a BoardId enumerator) and the git hash (PALP_GIT_HASH), and fills
// image_size and image_crc32 after the link (firmware/cmake/fill_metadata.cmake).
#include "palp/fw/controller.hpp"
#include "palp/protocol/image_metadata.hpp"

#ifndef PALP_IMAGE_BOARD
#error "PALP_IMAGE_BOARD names the image's board (a palp::proto::BoardId enumerator)"
#endif
#ifndef PALP_GIT_HASH
#define PALP_GIT_HASH ""
#endif

namespace {
using palp::proto::BoardId;
using palp::proto::ImageMetadata;
// The firmware version is the one the core reports in DeviceInfo (DeviceIdentity's defaults).
constexpr palp::fw::DeviceIdentity kCore{};
}  // namespace

// External, unmangled: `nm` shows palp_image_metadata at the image's 0x400.
extern "C" [[gnu::used, gnu::section(".palp_metadata")]] constinit const ImageMetadata
    palp_image_metadata = palp::proto::make_image_metadata(
        BoardId::PALP_IMAGE_BOARD, kCore.fw_major, kCore.fw_minor, kCore.fw_patch, PALP_GIT_HASH);
