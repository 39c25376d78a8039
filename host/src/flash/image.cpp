// SPDX-License-Identifier: Apache-2.0
// Reading and checking a firmware image before anything is flashed (palp/flash.hpp, step 1), the
// board check against a device (step 2) and the recovery text.
#include <filesystem>

#include "palp/error.hpp"
#include "palp/flash.hpp"
#include "palp/protocol/handshake.hpp"
#include "palp/protocol/image_file.hpp"
#include "palp/protocol/verdict_text.hpp"

namespace palp::flash {

namespace {
std::string three(unsigned a, unsigned b, unsigned c) {
  return std::to_string(a) + "." + std::to_string(b) + "." + std::to_string(c);
}
}  // namespace

std::string FirmwareImage::board() const {
  return proto::board_name(static_cast<proto::BoardId>(metadata.board));
}
std::string FirmwareImage::firmware_version() const {
  return three(metadata.fw_major, metadata.fw_minor, metadata.fw_patch);
}
std::string FirmwareImage::protocol_version() const {
  return proto::version_text(metadata.protocol_major, metadata.protocol_minor);
}

FirmwareImage read_image(const std::string& path) {
  bool file_error = false;
  const proto::ImageBytes file = proto::read_image_file(path, file_error);
  if (!file.error.empty()) throw ConfigError(path + ": " + file.error);
  const proto::ImageParse p = proto::parse_image_metadata(file.image.data(), file.image.size());
  if (!p.ok()) throw ConfigError(path + ": " + proto::describe_image_problem(p));
  const auto board = static_cast<proto::BoardId>(p.metadata.board);
  if (board == proto::BoardId::unknown || proto::board_name(board) == std::string("unknown"))
    throw ConfigError(path + ": the image is for board number " + std::to_string(p.metadata.board) +
                      ", which this palp does not know: use the palp release that built it");
  const std::string misplaced = proto::describe_load_address_problem(file, p.metadata);
  if (!misplaced.empty()) throw ConfigError(path + ": " + misplaced);

  FirmwareImage image;
  image.path = path;
  image.container = proto::image_container_name(file.container);
  image.address = proto::board_image_address(board);
  image.bytes = file.image;
  image.metadata = p.metadata;

  // the image must speak a protocol this SDK talks: else nothing could check the update
  const proto::ProtocolVersion speaks{p.metadata.protocol_major, p.metadata.protocol_minor,
                                      p.metadata.schema_hash};
  const proto::Verdict v = proto::judge(proto::kThisProtocol, speaks);
  if (v.compatibility == proto::Compatibility::incompatible) {
    const std::string ours = proto::version_text(proto::kProtocolMajor, proto::kProtocolMinor);
    std::string why = v.because == proto::IncompatibleBecause::major_differs
                          ? "the major versions differ"
                      : v.because == proto::IncompatibleBecause::unstable_minor
                          ? "protocol 0.x makes no compatibility promise and the minor versions differ"
                          : "the versions match but the schema hashes differ (" +
                                proto::hash_text(p.metadata.schema_hash) + " vs " +
                                proto::hash_text(proto::kSchemaHash) + "): one is an unreleased build";
    throw ConfigError(path + ": the image speaks protocol " + image.protocol_version() +
                      ", this palp SDK " + sdk_version() + " speaks " + ours + ": " + why +
                      ". This palpctl could not talk to the device after the update: flash with "
                      "the palpctl built with the image (or dfu-util, see firmware/README.md)");
  }

  const proto::FlashRange keep = proto::board_calibration_flash(board);
  const std::uint64_t end = std::uint64_t{image.address} + image.bytes.size();
  if (keep.begin != keep.end && end > keep.begin && image.address < keep.end)
    throw ConfigError(path + ": the image's " + std::to_string(image.bytes.size()) +
                      " bytes from " + proto::hash_text(image.address) +
                      " reach the calibration's flash at " + proto::hash_text(keep.begin) +
                      ": it is not a firmware image for this board");
  return image;
}

std::string board_mismatch(const FirmwareImage& image, const DeviceInfo& info) {
  if (info.board == image.board()) return "";
  return image.path + ": the image is for board " + image.board() + ", device " + info.serial +
         " is a " + info.board + ": nothing was changed; flash an image built for " + info.board;
}

std::string recovery_text(const FirmwareImage& image, bool mass_erased) {
  const std::filesystem::path p(image.path);
  std::string dfu_util;
  if (image.container == "DfuSe") {
    dfu_util = "dfu-util -a 0 -s :leave -D " + image.path;
  } else {
    std::string bin = image.path;
    if (image.container == "ELF") bin = (p.parent_path() / p.stem()).string() + ".bin";
    dfu_util = "dfu-util -a 0 -s " + proto::hash_text(image.address) + ":leave -D " + bin;
    if (image.container == "ELF") dfu_util += " (the .bin the build wrote beside the .elf)";
  }
  return std::string("The device waits in its ROM DFU bootloader (USB 0483:df11) until an image "
                     "is written; ") +
         (mass_erased ? "its calibration was erased too (mass erase): restore it from the file the "
                        "update wrote. "
                      : "its calibration pages were not erased. ") +
         "Recover with\n  palpctl flash --device-in-dfu " +
         image.path + "\nor with dfu-util:\n  " + dfu_util;
}

}  // namespace palp::flash
