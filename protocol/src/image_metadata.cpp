// SPDX-License-Identifier: Apache-2.0
// The image metadata parser (image_metadata.hpp): byte offsets read little-endian, so it reads
// the same on any host whatever its struct layout.
#include "palp/protocol/image_metadata.hpp"

#include "palp/protocol/crc32.hpp"

namespace palp::proto {

namespace {

constexpr std::size_t kCrcAt = kImageMetadataOffset + kImageCrcFieldOffset;

void copy_chars(char* out, const u8* in, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k) out[k] = static_cast<char>(in[k]);
}

ImageMetadata decode(const u8* block) {
  ImageMetadata m{};
  Reader r(block, kImageMetadataSize);
  u8 magic[sizeof m.magic];
  r.bytes(magic, sizeof magic);
  copy_chars(m.magic, magic, sizeof magic);
  r.scalar(m.layout_version);
  r.scalar(m.board);
  r.scalar(m.fw_major);
  r.scalar(m.fw_minor);
  r.scalar(m.fw_patch);
  r.scalar(m.reserved0);
  r.scalar(m.protocol_major);
  r.scalar(m.protocol_minor);
  r.scalar(m.reserved1);
  r.scalar(m.schema_hash);
  r.scalar(m.image_size);
  r.scalar(m.image_crc32);
  u8 hash[sizeof m.git_hash];
  r.bytes(hash, sizeof hash);
  copy_chars(m.git_hash, hash, sizeof hash);
  m.git_hash[sizeof m.git_hash - 1] = '\0';  // always a C string, whatever the image holds
  return m;
}

}  // namespace

u32 image_crc32(const u8* image, std::size_t size) {
  static constexpr u8 kZeros[4] = {0, 0, 0, 0};
  u32 s = crc32_update(kCrc32Init, image, kCrcAt);
  s = crc32_update(s, kZeros, sizeof kZeros);
  s = crc32_update(s, image + kCrcAt + 4, size - kCrcAt - 4);
  return crc32_final(s);
}

ImageParse parse_image_metadata(const u8* image, std::size_t size) {
  ImageParse p;
  if (image == nullptr || size < kImageMetadataOffset + kImageMetadataSize) {
    p.error = ImageError::too_short;
    p.expected = static_cast<u32>(kImageMetadataOffset + kImageMetadataSize);
    p.actual = static_cast<u32>(size);
    return p;
  }
  const u8* block = image + kImageMetadataOffset;
  for (std::size_t k = 0; k < sizeof kImageMagic; ++k) {
    if (block[k] != static_cast<u8>(kImageMagic[k])) {
      p.error = ImageError::no_magic;
      return p;
    }
  }
  p.metadata = decode(block);
  if (p.metadata.layout_version != kImageLayoutVersion) {
    p.error = ImageError::unknown_layout;
    p.expected = kImageLayoutVersion;
    p.actual = p.metadata.layout_version;
    return p;
  }
  if (p.metadata.image_size == 0) {
    p.error = ImageError::not_filled;
    return p;
  }
  if (p.metadata.image_size != size) {
    p.error = ImageError::size_mismatch;
    p.expected = p.metadata.image_size;
    p.actual = static_cast<u32>(size);
    return p;
  }
  const u32 crc = image_crc32(image, size);
  if (crc != p.metadata.image_crc32) {
    p.error = ImageError::crc_mismatch;
    p.expected = p.metadata.image_crc32;
    p.actual = crc;
  }
  return p;
}

const char* image_error_name(ImageError error) {
  switch (error) {
    case ImageError::none: return "none";
    case ImageError::too_short: return "too short";
    case ImageError::no_magic: return "no magic";
    case ImageError::unknown_layout: return "unknown layout";
    case ImageError::not_filled: return "not filled";
    case ImageError::size_mismatch: return "size mismatch";
    case ImageError::crc_mismatch: return "CRC mismatch";
  }
  return "?";
}

}  // namespace palp::proto
