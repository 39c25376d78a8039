// SPDX-License-Identifier: Apache-2.0
// Firmware image files for the tests of palp::flash and `palpctl flash`: a .bin with a filled
// metadata block (image_metadata.hpp), as fill_metadata.cmake leaves it, and its variants (a
// corrupted byte, another board, another protocol).
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "palp/protocol/image_metadata.hpp"

namespace palp::test {

struct ImageSpec {
  proto::BoardId board = proto::BoardId::stm32g474;
  std::uint8_t fw_major = 0, fw_minor = 1, fw_patch = 0;  ///< palp-sim's firmware version
  std::uint8_t protocol_major = proto::kProtocolMajor, protocol_minor = proto::kProtocolMinor;
  std::uint32_t schema_hash = proto::kSchemaHash;
  std::size_t size = 6000;  ///< bytes (three 2 KB pages)
};

/// The image's bytes: a recognisable pattern, the metadata at 0x400, size and CRC filled.
inline std::vector<std::uint8_t> make_image(const ImageSpec& s = {}) {
  std::vector<std::uint8_t> b(s.size);
  for (std::size_t k = 0; k < b.size(); ++k) b[k] = static_cast<std::uint8_t>((k * 13) ^ (k >> 8));
  proto::ImageMetadata m =
      proto::make_image_metadata(s.board, s.fw_major, s.fw_minor, s.fw_patch, "abc1234");
  m.protocol_major = s.protocol_major;
  m.protocol_minor = s.protocol_minor;
  m.schema_hash = s.schema_hash;
  m.image_size = static_cast<std::uint32_t>(b.size());
  m.image_crc32 = 0;
  std::memcpy(b.data() + proto::kImageMetadataOffset, &m, sizeof m);
  const std::uint32_t crc = proto::image_crc32(b.data(), b.size());
  std::memcpy(b.data() + proto::kImageMetadataOffset + proto::kImageCrcFieldOffset, &crc, 4);
  return b;
}

inline void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace palp::test
