// SPDX-License-Identifier: Apache-2.0
// The image metadata block (image_metadata.hpp) and the image files it is read from
// (image_file.hpp), on images built byte by byte here from the layout in the header's comment
// and the DfuSe/ELF formats; CRCs are known answers computed independently (Python's zlib.crc32).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "palp/protocol/crc32.hpp"
#include "palp/protocol/image_file.hpp"
#include "palp/protocol/image_metadata.hpp"

namespace palp::proto {
namespace {

void put16(std::vector<u8>& b, std::size_t at, u16 v) {
  b[at] = static_cast<u8>(v);
  b[at + 1] = static_cast<u8>(v >> 8);
}
void put32(std::vector<u8>& b, std::size_t at, u32 v) {
  for (int k = 0; k < 4; ++k) b[at + k] = static_cast<u8>(v >> (8 * k));
}
void append32(std::vector<u8>& b, u32 v) {
  b.resize(b.size() + 4);
  put32(b, b.size() - 4, v);
}

// 2048 bytes of (k * 7 + 3) with a layout-1 block at 0x400 written field by field: board
// stm32g474, firmware 2.3.4, protocol 1.1, schema 0x12345678, git "abc1234", size 2048, CRC
// 0x498dd5e4 (zlib.crc32 of the image with the CRC field zero).
constexpr u32 kKnownCrc = 0x498dd5e4u;
std::vector<u8> known_image(bool fill = true) {
  std::vector<u8> b(2048);
  for (std::size_t k = 0; k < b.size(); ++k) b[k] = static_cast<u8>(k * 7 + 3);
  std::vector<u8> block(48, 0);
  std::memcpy(block.data(), "palp-img", 8);
  put16(block, 8, 1);
  put16(block, 10, 1);
  block[12] = 2, block[13] = 3, block[14] = 4;
  block[16] = 1, block[17] = 1;
  put32(block, 20, 0x12345678u);
  if (fill) put32(block, 24, 2048);
  std::memcpy(block.data() + 32, "abc1234", 7);
  std::copy(block.begin(), block.end(), b.begin() + 0x400);
  if (fill) put32(b, 0x41c, kKnownCrc);
  return b;
}

ImageParse parse(const std::vector<u8>& b) { return parse_image_metadata(b.data(), b.size()); }

TEST(ImageMetadata, KnownImageParsesWithEveryFieldAndItsCrcIsTheKnownAnswer) {
  const auto b = known_image();
  EXPECT_EQ(image_crc32(b.data(), b.size()), kKnownCrc);
  const ImageParse p = parse(b);
  ASSERT_TRUE(p.ok()) << image_error_name(p.error);
  EXPECT_EQ(p.metadata.board, static_cast<u16>(BoardId::stm32g474));
  EXPECT_EQ(p.metadata.fw_major, 2);
  EXPECT_EQ(p.metadata.fw_minor, 3);
  EXPECT_EQ(p.metadata.fw_patch, 4);
  EXPECT_EQ(p.metadata.schema_hash, 0x12345678u);
  EXPECT_EQ(p.metadata.image_size, 2048u);
  EXPECT_STREQ(p.metadata.git_hash, "abc1234");
  EXPECT_EQ(format_image_metadata(p.metadata),
            "board: stm32g474 (1)\nfirmware_version: 2.3.4\nprotocol_version: 1.1\n"
            "schema_hash: 0x12345678\ngit_hash: abc1234\nimage_size: 2048 bytes\n"
            "image_crc32: 0x498dd5e4\nmetadata_layout: 1 at offset 0x400\n");
}

TEST(ImageMetadata, TheFirmwaresBlockHasTheHandWrittenLayoutWithThisBuildsProtocol) {
  const ImageMetadata m = make_image_metadata(BoardId::stm32g474, 2, 3, 4, "abc1234");
  std::vector<u8> expected = known_image(false);
  expected.assign(expected.begin() + 0x400, expected.begin() + 0x430);
  expected[16] = kProtocolMajor;
  expected[17] = kProtocolMinor;
  put32(expected, 20, kSchemaHash);
  std::vector<u8> got(sizeof m);
  std::memcpy(got.data(), &m, sizeof m);
  EXPECT_EQ(got, expected);
}

TEST(ImageMetadata, AFlippedByteIsACrcMismatchNamingStoredAndComputedValues) {
  auto b = known_image();
  b[100] ^= 0x01;
  const ImageParse p = parse(b);
  EXPECT_EQ(p.error, ImageError::crc_mismatch);
  EXPECT_EQ(p.expected, kKnownCrc);
  EXPECT_EQ(p.actual, 0x49cc4cf4u);
  EXPECT_EQ(describe_image_problem(p),
            "CRC mismatch: the metadata says 0x498dd5e4, the image's bytes give 0x49cc4cf4: the "
            "image is corrupt");
}

TEST(ImageMetadata, TheCrcFieldItselfIsExcludedButTheSizeFieldIsCovered) {
  auto b = known_image();
  b[0x418] ^= 0x01;  // image_size's low byte: now 2049, a size mismatch first
  EXPECT_EQ(parse(b).error, ImageError::size_mismatch);
  b = known_image();
  b[0x41f] ^= 0x80;  // the stored CRC: the computed one is still the known answer
  const ImageParse p = parse(b);
  EXPECT_EQ(p.error, ImageError::crc_mismatch);
  EXPECT_EQ(p.actual, kKnownCrc);
  EXPECT_EQ(p.expected, kKnownCrc ^ 0x80000000u);
}

TEST(ImageMetadata, ATruncatedImageIsASizeMismatchWithBothSizes) {
  auto b = known_image();
  b.resize(1500);
  const ImageParse p = parse(b);
  EXPECT_EQ(p.error, ImageError::size_mismatch);
  EXPECT_EQ(describe_image_problem(p),
            "size mismatch: the metadata says 2048 bytes, the image has 1500: it is truncated or "
            "has bytes added");
}

TEST(ImageMetadata, ShortFilesAndOtherBytesAreNotImages) {
  auto b = known_image();
  b.resize(0x42f);
  EXPECT_EQ(describe_image_problem(parse(b)),
            "not a palp firmware image: 1071 bytes, fewer than the 1072 that reach the end of the "
            "metadata block");
  b = known_image();
  b[0x403] = 'q';
  EXPECT_EQ(describe_image_problem(parse(b)),
            "not a palp firmware image: no \"palp-img\" metadata block at offset 0x00000400");
  EXPECT_EQ(parse_image_metadata(nullptr, 0).error, ImageError::too_short);
}

TEST(ImageMetadata, AnUnknownLayoutAndAnUnfilledBlockAreNamed) {
  auto b = known_image();
  put16(b, 0x408, 2);
  EXPECT_EQ(describe_image_problem(parse(b)),
            "unknown layout: metadata layout 2, this build reads layout 1");
  EXPECT_EQ(describe_image_problem(parse(known_image(false))),
            "not filled: image_size is 0: the post-build step (firmware/cmake/fill_metadata.cmake) "
            "did not run on this image");
}

// ---- containers -------------------------------------------------------------------------------

// A DfuSe file per usb-dfu-facts.md §6.1/§6.2: one target, one element at 0x08000000, suffix
// 0483:df11 bcdDFU 0x011A; its dwCRC for the known image is 0x443e851f (zlib.crc32 ^ 0xffffffff).
std::vector<u8> known_dfu() {
  const auto image = known_image();
  std::vector<u8> d = {'D', 'f', 'u', 'S', 'e', 1};
  append32(d, static_cast<u32>(11 + 274 + 8 + image.size() + 16));
  d.push_back(1);
  for (char c : std::string("Target")) d.push_back(static_cast<u8>(c));
  d.push_back(0);
  append32(d, 1);
  std::string name = "Internal Flash";
  name.resize(255, '\0');
  d.insert(d.end(), name.begin(), name.end());
  append32(d, static_cast<u32>(8 + image.size()));
  append32(d, 1);
  append32(d, 0x08000000u);
  append32(d, static_cast<u32>(image.size()));
  d.insert(d.end(), image.begin(), image.end());
  const u8 suffix[] = {0xFF, 0xFF, 0x11, 0xDF, 0x83, 0x04, 0x1A, 0x01, 'U', 'F', 'D', 16};
  d.insert(d.end(), std::begin(suffix), std::end(suffix));
  append32(d, 0x443e851fu);
  return d;
}

TEST(ImageFile, ADfuSeFileYieldsItsElementAndAddress) {
  const ImageBytes got = extract_image(known_dfu());
  ASSERT_EQ(got.error, "");
  EXPECT_EQ(got.container, ImageContainer::dfu);
  EXPECT_EQ(got.load_address, 0x08000000u);
  EXPECT_EQ(got.image, known_image());
}

TEST(ImageFile, AnImageLoadedAwayFromItsBoardsFlashIsNamed) {
  ImageBytes file = extract_image(known_dfu());
  const ImageMetadata m = parse(file.image).metadata;
  EXPECT_EQ(describe_load_address_problem(file, m), "");
  file.load_address = 0;
  EXPECT_EQ(describe_load_address_problem(file, m),
            "load address 0x00000000, but stm32g474 images start at 0x08000000");
  file.has_load_address = false;  // a .bin says nothing about where it goes
  EXPECT_EQ(describe_load_address_problem(file, m), "");
}

TEST(ImageFile, ACorruptDfuSeFileIsASuffixCrcMismatchWithBothValues) {
  auto d = known_dfu();
  d[500] ^= 0x80;
  EXPECT_EQ(extract_image(d).error,
            "DFU suffix CRC mismatch: the suffix says 0x443e851f, the file's bytes give "
            "0x83afea4b: the file is corrupt");
}

TEST(ImageFile, ADfuSeFileWithTwoElementsIsRefused) {
  auto d = known_dfu();
  put32(d, 11 + 270, 2);
  // re-seal the suffix so the count, not the CRC, is what is refused
  u32 s = kCrc32Init;
  s = crc32_update(s, d.data(), d.size() - 4);
  put32(d, d.size() - 4, s);
  EXPECT_EQ(extract_image(d).error,
            "a DfuSe file with other than one target holding one element (the firmware's .dfu "
            "has one)");
}

// A 32-bit little-endian ELF as a linker writes it: .text at 0x08000000 (0x40 bytes of 0x11),
// .data run at 0x20000000 but loaded at 0x08000100 (8 bytes of 0x22), .bss (no bytes).
std::vector<u8> small_elf() {
  std::vector<u8> f(0x300, 0);
  const u8 ident[] = {0x7F, 'E', 'L', 'F', 1, 1, 1};
  std::memcpy(f.data(), ident, sizeof ident);
  put32(f, 28, 52);     // e_phoff
  put32(f, 32, 0x220);  // e_shoff
  put16(f, 42, 32), put16(f, 44, 2), put16(f, 46, 40), put16(f, 48, 4);
  auto segment = [&](std::size_t at, u32 offset, u32 vaddr, u32 paddr, u32 size) {
    put32(f, at, 1), put32(f, at + 4, offset), put32(f, at + 8, vaddr), put32(f, at + 12, paddr);
    put32(f, at + 16, size), put32(f, at + 20, size);
  };
  segment(52, 0x100, 0x08000000u, 0x08000000u, 0x40);
  segment(84, 0x200, 0x20000000u, 0x08000100u, 0x108);
  auto section = [&](int n, u32 type, u32 addr, u32 offset, u32 size) {
    const std::size_t at = 0x220 + 40 * static_cast<std::size_t>(n);
    put32(f, at + 4, type), put32(f, at + 8, 0x2 /* ALLOC */), put32(f, at + 12, addr);
    put32(f, at + 16, offset), put32(f, at + 20, size);
  };
  section(1, 1, 0x08000000u, 0x100, 0x40);
  section(2, 1, 0x20000000u, 0x200, 8);
  section(3, 8, 0x20000008u, 0x208, 0x100);
  std::memset(f.data() + 0x100, 0x11, 0x40);
  std::memset(f.data() + 0x200, 0x22, 8);
  return f;
}

TEST(ImageFile, AnElfYieldsWhatObjcopyBinaryWrites) {
  const ImageBytes got = extract_image(small_elf());
  ASSERT_EQ(got.error, "");
  EXPECT_EQ(got.container, ImageContainer::elf);
  EXPECT_EQ(got.load_address, 0x08000000u);
  std::vector<u8> expected(0x108, 0);
  std::fill_n(expected.begin(), 0x40, 0x11);
  std::fill_n(expected.begin() + 0x100, 8, 0x22);
  EXPECT_EQ(got.image, expected);
}

TEST(ImageFile, ATruncatedElfIsRefused) {
  auto f = small_elf();
  f.resize(0x240);  // the section headers are cut
  EXPECT_EQ(extract_image(f).error, "ELF headers point outside the file (truncated?)");
}

// Every cut of the files above: refused with a reason, never read past the end (the asan build
// runs these too).
TEST(ImageFile, EveryTruncationOfAnElfBeforeItsSectionHeadersEndIsRefused) {
  const auto full = small_elf();
  for (std::size_t n = 4; n < 0x220 + 4 * 40; ++n) {
    const std::vector<u8> cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_NE(extract_image(cut).error, "") << n << " bytes";
  }
}

TEST(ImageFile, NoTruncationOfADfuSeFileYieldsAnImageFromIt) {
  const auto full = known_dfu();
  for (std::size_t n = 0; n < full.size(); ++n) {
    const std::vector<u8> cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(n));
    const ImageBytes got = extract_image(cut);
    EXPECT_TRUE(!got.error.empty() || got.container == ImageContainer::bin) << n << " bytes";
    if (got.error.empty()) {
      EXPECT_FALSE(parse(got.image).ok()) << n << " bytes";
    }
  }
}

TEST(ImageFile, OtherBytesAreTakenAsABinAndAnOversizedOneIsRefused) {
  const ImageBytes got = extract_image(known_image());
  EXPECT_EQ(got.container, ImageContainer::bin);
  EXPECT_FALSE(got.has_load_address);
  EXPECT_EQ(extract_image(std::vector<u8>(kMaxImageBytes + 1, 0xFF)).error,
            "the file is 2097153 bytes, more than the 2097152 bytes an image may have");
}

}  // namespace
}  // namespace palp::proto
