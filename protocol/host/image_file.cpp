// SPDX-License-Identifier: Apache-2.0
// Images from .elf/.bin/.dfu files and their metadata as text (image_file.hpp).
#include "palp/protocol/image_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "palp/protocol/crc32.hpp"
#include "palp/protocol/verdict_text.hpp"

namespace palp::proto {

namespace {

u32 le32(const std::vector<u8>& b, std::size_t at) {
  return static_cast<u32>(b[at]) | (static_cast<u32>(b[at + 1]) << 8) |
         (static_cast<u32>(b[at + 2]) << 16) | (static_cast<u32>(b[at + 3]) << 24);
}
u16 le16(const std::vector<u8>& b, std::size_t at) {
  return static_cast<u16>(b[at] | (b[at + 1] << 8));
}
std::string hex32(u32 v) { return hash_text(v); }
bool fits(std::size_t at, std::size_t n, std::size_t size) { return at <= size && n <= size - at; }

// ---- ELF: what `objcopy -O binary` writes ------------------------------------------------------
constexpr u32 kShfAlloc = 0x2, kShtNobits = 8, kPtLoad = 1;

ImageBytes from_elf(const std::vector<u8>& f) {
  ImageBytes out;
  out.container = ImageContainer::elf;
  if (f.size() < 52 || f[4] != 1 || f[5] != 1) {
    out.error = "not a 32-bit little-endian ELF file (the firmware's .elf is one)";
    return out;
  }
  const u32 phoff = le32(f, 28), shoff = le32(f, 32);
  const u16 phentsize = le16(f, 42), phnum = le16(f, 44), shentsize = le16(f, 46),
            shnum = le16(f, 48);
  if (phentsize < 32 || shentsize < 40 || !fits(phoff, std::size_t{phentsize} * phnum, f.size()) ||
      !fits(shoff, std::size_t{shentsize} * shnum, f.size())) {
    out.error = "ELF headers point outside the file (truncated?)";
    return out;
  }
  struct Piece {
    u32 lma;
    std::size_t offset, size;
  };
  std::vector<Piece> pieces;
  for (u16 s = 0; s < shnum; ++s) {
    const std::size_t sh = shoff + std::size_t{s} * shentsize;
    const u32 type = le32(f, sh + 4), flags = le32(f, sh + 8), addr = le32(f, sh + 12),
              offset = le32(f, sh + 16), size = le32(f, sh + 20);
    if (!(flags & kShfAlloc) || type == kShtNobits || size == 0) continue;
    if (!fits(offset, size, f.size())) {
      out.error = "an ELF section's bytes lie outside the file (truncated?)";
      return out;
    }
    u32 lma = addr;  // the load address: through the PT_LOAD segment that holds the section
    for (u16 p = 0; p < phnum; ++p) {
      const std::size_t ph = phoff + std::size_t{p} * phentsize;
      const u32 vaddr = le32(f, ph + 8), paddr = le32(f, ph + 12), memsz = le32(f, ph + 20);
      if (le32(f, ph) == kPtLoad && addr >= vaddr && addr - vaddr < memsz) {
        lma = paddr + (addr - vaddr);
        break;
      }
    }
    pieces.push_back({lma, offset, size});
  }
  if (pieces.empty()) {
    out.error = "the ELF file has no loadable bytes";
    return out;
  }
  const auto lo = std::min_element(pieces.begin(), pieces.end(),
                                   [](const Piece& a, const Piece& b) { return a.lma < b.lma; });
  u64 end = 0;
  for (const Piece& p : pieces) end = std::max<u64>(end, u64{p.lma} + p.size);
  const u64 span = end - lo->lma;
  if (span > kMaxImageBytes) {
    out.error = "the ELF's loadable bytes span " + std::to_string(span) + " bytes from " +
                hex32(lo->lma) + ", more than the " + std::to_string(kMaxImageBytes) +
                " bytes an image may have";
    return out;
  }
  out.load_address = lo->lma;
  out.has_load_address = true;
  out.image.assign(static_cast<std::size_t>(span), 0);
  for (const Piece& p : pieces)
    std::copy_n(f.begin() + static_cast<std::ptrdiff_t>(p.offset), p.size,
                out.image.begin() + static_cast<std::ptrdiff_t>(p.lma - lo->lma));
  return out;
}

// ---- DfuSe ------------------------------------------------------------------------------------
constexpr std::size_t kSuffix = 16, kPrefix = 11, kTargetPrefix = 274, kElementHeader = 8;

bool has_dfu_suffix(const std::vector<u8>& f) {
  return f.size() >= kSuffix && f[f.size() - 8] == 'U' && f[f.size() - 7] == 'F' &&
         f[f.size() - 6] == 'D';
}

ImageBytes from_dfu(const std::vector<u8>& f) {
  ImageBytes out;
  out.container = ImageContainer::dfu;
  const std::size_t n = f.size();
  const u32 stored = le32(f, n - 4);
  const u32 computed = crc32_update(kCrc32Init, f.data(), n - 4);  // no final XOR (facts §6.1)
  if (stored != computed) {
    out.error = "DFU suffix CRC mismatch: the suffix says " + hex32(stored) +
                ", the file's bytes give " + hex32(computed) + ": the file is corrupt";
    return out;
  }
  if (f[n - 5] != kSuffix) {
    out.error = "DFU suffix length " + std::to_string(f[n - 5]) + ", expected 16";
    return out;
  }
  if (n < kPrefix + kSuffix || std::string(f.begin(), f.begin() + 5) != "DfuSe" || f[5] != 1) {
    out.error = "a DFU file without a DfuSe v1 prefix (plain DFU files carry no address)";
    return out;
  }
  if (le32(f, 6) != n) {
    out.error = "DfuSe prefix says " + std::to_string(le32(f, 6)) + " bytes, the file has " +
                std::to_string(n);
    return out;
  }
  const std::size_t target = kPrefix;
  if (f[10] != 1 || !fits(target, kTargetPrefix + kElementHeader, n - kSuffix) ||
      le32(f, target + 270) != 1) {
    out.error = "a DfuSe file with other than one target holding one element (the firmware's "
                ".dfu has one)";
    return out;
  }
  const std::size_t element = target + kTargetPrefix;
  const u32 target_size = le32(f, target + 266), size = le32(f, element + 4);
  if (target_size != kElementHeader + u64{size} ||
      element + kElementHeader + u64{size} != n - kSuffix) {
    out.error = "DfuSe sizes disagree: target " + std::to_string(target_size) + " bytes, element " +
                std::to_string(size) + " bytes, " + std::to_string(n - kSuffix - element) +
                " bytes between the target prefix and the suffix";
    return out;
  }
  out.load_address = le32(f, element);
  out.has_load_address = true;
  out.image.assign(f.begin() + static_cast<std::ptrdiff_t>(element + kElementHeader),
                   f.end() - static_cast<std::ptrdiff_t>(kSuffix));
  return out;
}

}  // namespace

const char* image_container_name(ImageContainer c) {
  switch (c) {
    case ImageContainer::bin: return "bin";
    case ImageContainer::elf: return "ELF";
    case ImageContainer::dfu: return "DfuSe";
  }
  return "?";
}

ImageBytes extract_image(const std::vector<u8>& file) {
  if (file.size() >= 4 && file[0] == 0x7F && file[1] == 'E' && file[2] == 'L' && file[3] == 'F')
    return from_elf(file);
  if (has_dfu_suffix(file)) return from_dfu(file);
  ImageBytes out;
  if (file.size() > kMaxImageBytes) {
    out.error = "the file is " + std::to_string(file.size()) + " bytes, more than the " +
                std::to_string(kMaxImageBytes) + " bytes an image may have";
    return out;
  }
  out.image = file;
  return out;
}

ImageBytes read_image_file(const std::string& path, bool& file_error) {
  file_error = false;
  ImageBytes out;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    file_error = true;
    out.error = "cannot open " + path + ": " + std::strerror(errno);
    return out;
  }
  std::vector<u8> bytes(kMaxImageFileBytes + 1);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) {
    file_error = true;
    out.error = "cannot read " + path;
    return out;
  }
  if (bytes.size() > kMaxImageFileBytes) {
    file_error = true;
    out.error = path + " is larger than " + std::to_string(kMaxImageFileBytes) +
                " bytes: not a firmware file";
    return out;
  }
  return extract_image(bytes);
}

std::string describe_load_address_problem(const ImageBytes& file, const ImageMetadata& m) {
  const auto board = static_cast<BoardId>(m.board);
  if (!file.has_load_address || board == BoardId::unknown ||
      file.load_address == board_image_address(board))
    return "";
  return "load address " + hex32(file.load_address) + ", but " + board_name(board) +
         " images start at " + hex32(board_image_address(board));
}

std::string format_image_metadata(const ImageMetadata& m) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "board: %s (%u)\n"
                "firmware_version: %u.%u.%u\n"
                "protocol_version: %u.%u\n"
                "schema_hash: %s\n"
                "git_hash: %s\n"
                "image_size: %u bytes\n"
                "image_crc32: %s\n"
                "metadata_layout: %u at offset 0x%zx\n",
                board_name(static_cast<BoardId>(m.board)), m.board, m.fw_major, m.fw_minor,
                m.fw_patch, m.protocol_major, m.protocol_minor, hex32(m.schema_hash).c_str(),
                m.git_hash, m.image_size, hex32(m.image_crc32).c_str(), m.layout_version,
                kImageMetadataOffset);
  return buf;
}

std::string describe_image_problem(const ImageParse& p) {
  const std::string name = image_error_name(p.error);
  switch (p.error) {
    case ImageError::none: return "";
    case ImageError::too_short:
      return "not a palp firmware image: " + std::to_string(p.actual) +
             " bytes, fewer than the " + std::to_string(p.expected) +
             " that reach the end of the metadata block";
    case ImageError::no_magic:
      return "not a palp firmware image: no \"palp-img\" metadata block at offset " +
             hex32(kImageMetadataOffset);
    case ImageError::unknown_layout:
      return name + ": metadata layout " + std::to_string(p.actual) + ", this build reads layout " +
             std::to_string(p.expected);
    case ImageError::not_filled:
      return name + ": image_size is 0: the post-build step (firmware/cmake/fill_metadata.cmake) "
                    "did not run on this image";
    case ImageError::size_mismatch:
      return name + ": the metadata says " + std::to_string(p.expected) + " bytes, the image has " +
             std::to_string(p.actual) + ": it is truncated or has bytes added";
    case ImageError::crc_mismatch:
      return name + ": the metadata says " + hex32(p.expected) + ", the image's bytes give " +
             hex32(p.actual) + ": the image is corrupt";
  }
  return name;
}

}  // namespace palp::proto
