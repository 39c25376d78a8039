// SPDX-License-Identifier: Apache-2.0
// The metadata block of a palp firmware image: what the image is (board, firmware version,
// protocol version and schema hash) and how to check it is whole (size, CRC-32), read by the
// host before anything is flashed. One definition: the firmware places an ImageMetadata in
// section .palp_metadata (firmware/app/src/image_metadata.cpp), the host parses it here.
//
// Where: at byte kImageMetadataOffset (0x400) of the image, i.e. of the .bin (flash address
// 0x08000400 on the STM32G474, 0x400 on QEMU's mps2-an386): right after the vector table
// (both boards' tables are shorter; the linker scripts ASSERT it).
//
// Layout 1, 48 bytes, little-endian, no padding (offsets in bytes):
//    0  char[8]  magic           "palp-img"
//    8  u16      layout_version  1 (kImageLayoutVersion)
//   10  u16      board           BoardId (board_id.hpp)
//   12  u8 x 3   fw_major, fw_minor, fw_patch  as the core reports them (DeviceInfo)
//   15  u8       reserved        0
//   16  u8 x 2   protocol_major, protocol_minor  (messages.hpp: kProtocolMajor/Minor)
//   18  u16      reserved        0
//   20  u32      schema_hash     (schema.hpp: kSchemaHash)
//   24  u32      image_size      bytes of the image from its first byte (the .bin's length)
//   28  u32      image_crc32     CRC-32/ISO-HDLC (crc32.hpp) of the image's image_size bytes
//                                with these four bytes taken as zeros
//   32  char[16] git_hash        `git describe --always --dirty` at configure, NUL-padded
//
// The build fills everything but image_size and image_crc32 at compile time; those two are 0 in
// the linked ELF and written after the link by firmware/cmake/fill_metadata.cmake into the .elf
// and the .bin (firmware/README.md, "Image metadata and the .dfu"). A new layout (fields added,
// moved or resized) gets a new layout_version; the parser refuses layouts it does not know.
//
// Freestanding: no heap, no exceptions; builds for the host and for Cortex-M4.
#pragma once

#include <cstddef>
#include <cstdint>

#include "palp/protocol/board_id.hpp"
#include "palp/protocol/messages.hpp"
#include "palp/protocol/schema.hpp"
#include "palp/protocol/wire_types.hpp"

namespace palp::proto {

inline constexpr std::size_t kImageMetadataOffset = 0x400;
inline constexpr u16 kImageLayoutVersion = 1;
inline constexpr char kImageMagic[8] = {'p', 'a', 'l', 'p', '-', 'i', 'm', 'g'};

/// The block as it lies in flash (layout 1), and the parser's result.
struct ImageMetadata {
  char magic[8];
  u16 layout_version;
  u16 board;  ///< a BoardId (kept as its number: an image may name a board this build lacks)
  u8 fw_major, fw_minor, fw_patch;
  u8 reserved0;
  u8 protocol_major, protocol_minor;
  u16 reserved1;
  u32 schema_hash;
  u32 image_size;
  u32 image_crc32;
  char git_hash[16];
};

inline constexpr std::size_t kImageMetadataSize = 48;
inline constexpr std::size_t kImageSizeFieldOffset = 24;  ///< within the block
inline constexpr std::size_t kImageCrcFieldOffset = 28;   ///< within the block
static_assert(sizeof(ImageMetadata) == kImageMetadataSize);
static_assert(offsetof(ImageMetadata, layout_version) == 8);
static_assert(offsetof(ImageMetadata, board) == 10);
static_assert(offsetof(ImageMetadata, fw_major) == 12);
static_assert(offsetof(ImageMetadata, protocol_major) == 16);
static_assert(offsetof(ImageMetadata, schema_hash) == 20);
static_assert(offsetof(ImageMetadata, image_size) == kImageSizeFieldOffset);
static_assert(offsetof(ImageMetadata, image_crc32) == kImageCrcFieldOffset);
static_assert(offsetof(ImageMetadata, git_hash) == 32);

/// The block a firmware build places in .palp_metadata: this build's protocol version and schema
/// hash, the given board, version and git hash (cut to 15 characters), size and CRC zero.
constexpr ImageMetadata make_image_metadata(BoardId board, u8 fw_major, u8 fw_minor, u8 fw_patch,
                                            const char* git_hash) {
  ImageMetadata m{};
  for (std::size_t k = 0; k < sizeof m.magic; ++k) m.magic[k] = kImageMagic[k];
  m.layout_version = kImageLayoutVersion;
  m.board = static_cast<u16>(board);
  m.fw_major = fw_major;
  m.fw_minor = fw_minor;
  m.fw_patch = fw_patch;
  m.protocol_major = kProtocolMajor;
  m.protocol_minor = kProtocolMinor;
  m.schema_hash = kSchemaHash;
  for (std::size_t k = 0; git_hash != nullptr && k + 1 < sizeof m.git_hash; ++k) {
    if (git_hash[k] == '\0') break;
    m.git_hash[k] = git_hash[k];
  }
  return m;
}

/// Why an image's metadata was refused. `expected`/`actual` carry the numbers the message needs.
enum class ImageError : u8 {
  none,
  too_short,       ///< fewer bytes than offset + block: actual = bytes given
  no_magic,        ///< no "palp-img" at kImageMetadataOffset: not a palp image
  unknown_layout,  ///< actual = the layout_version found, expected = kImageLayoutVersion
  not_filled,      ///< image_size is 0: the post-build fill_metadata step did not run
  size_mismatch,   ///< expected = image_size in the block, actual = bytes given
  crc_mismatch,    ///< expected = image_crc32 in the block, actual = CRC computed over the bytes
};

struct ImageParse {
  ImageError error = ImageError::none;
  u32 expected = 0, actual = 0;
  ImageMetadata metadata{};  ///< decoded whenever the magic and layout were recognised
  constexpr bool ok() const { return error == ImageError::none; }
};

/// Reads and checks the metadata of `image` (the image's bytes from its first, as in the .bin):
/// magic, layout, size == `size`, CRC. Checks in that order; the first failure is reported.
ImageParse parse_image_metadata(const u8* image, std::size_t size);

/// The CRC the block must hold: CRC-32/ISO-HDLC of image[0, size) with the four bytes of the
/// image_crc32 field as zeros (size must be >= kImageMetadataOffset + kImageMetadataSize).
u32 image_crc32(const u8* image, std::size_t size);

/// "too short", "no magic", ...: the error's name.
const char* image_error_name(ImageError error);

}  // namespace palp::proto
