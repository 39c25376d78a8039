// SPDX-License-Identifier: Apache-2.0
// A firmware image's bytes from the files the build writes (.elf, .bin, .dfu), and its metadata
// (image_metadata.hpp) as text: `palp-proto image FILE`, and the SDK before it flashes. Host only.
//
//   .bin  the image as is (byte 0 = the first flash byte)
//   .elf  the loadable sections at their load addresses, gaps as zeros: what `objcopy -O binary`
//         writes (32-bit little-endian ELF only)
//   .dfu  the one element of the one target of a DfuSe file, after its suffix CRC and its sizes
//         check out (../shared/reference/usb-dfu-facts.md §6)
// The container is told by content (ELF magic; a DFU suffix "UFD" with a "DfuSe" prefix), not by
// the file name. Files are read up to kMaxImageFileBytes, images up to kMaxImageBytes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "palp/protocol/image_metadata.hpp"

namespace palp::proto {

inline constexpr std::size_t kMaxImageFileBytes = 16u << 20;  ///< an .elf with debug info fits
inline constexpr std::size_t kMaxImageBytes = 2u << 20;       ///< 4 x the STM32G474's flash

enum class ImageContainer : u8 { bin, elf, dfu };
const char* image_container_name(ImageContainer c);  ///< "bin", "ELF", "DfuSe"

struct ImageBytes {
  std::string error;  ///< empty: ok; else why the file holds no image (one sentence)
  ImageContainer container = ImageContainer::bin;
  u32 load_address = 0;  ///< ELF: lowest load address; DfuSe: the element's address; bin: 0
  bool has_load_address = false;
  std::vector<u8> image;
};

/// The image inside a file's bytes (any of the three containers).
ImageBytes extract_image(const std::vector<u8>& file);

/// Reads `path` (refusing more than kMaxImageFileBytes) and extracts the image; a file that
/// cannot be read sets `error` and `file_error`.
ImageBytes read_image_file(const std::string& path, bool& file_error);

/// Empty when the file's load address (ELF, DfuSe) is where the metadata's board starts its images
/// (board_image_address) or the file carries none (bin) or the board is unknown; else one sentence:
/// "load address 0x00000000, but stm32g474 images start at 0x08000000".
std::string describe_load_address_problem(const ImageBytes& file, const ImageMetadata& m);

/// The metadata as lines "name: value unit", e.g. "image_size: 74120 bytes".
std::string format_image_metadata(const ImageMetadata& m);

/// Why the metadata was refused, one sentence naming the numbers: e.g. "CRC mismatch: the
/// metadata says 0x805e5535, the image's bytes give 0x1f0c3a2b: the image is corrupt".
std::string describe_image_problem(const ImageParse& p);

}  // namespace palp::proto
