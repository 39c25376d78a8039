// SPDX-License-Identifier: Apache-2.0
// palp::flash before any device is involved: reading and refusing images (palp/flash.hpp step 1),
// the board check's text, the recovery text, and the kept calibration's file rules.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "firmware_image.hpp"
#include "flash/calibration_file.hpp"
#include "palp/error.hpp"
#include "palp/flash.hpp"
#include "palp/protocol/verdict_text.hpp"

namespace palp::flash {
namespace {

namespace fs = std::filesystem;
using test::ImageSpec;
using test::make_image;

class FlashImage : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("palp-flash-image-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name, const std::vector<std::uint8_t>& bytes) {
    const std::string p = (dir_ / name).string();
    test::write_file(p, bytes);
    return p;
  }
  static std::string refusal(const std::string& path) {
    try {
      read_image(path);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "no ConfigError";
  }
  fs::path dir_;
};

TEST_F(FlashImage, AGoodBinReadsWithItsBoardVersionsAndTheBoardsAddress) {
  const auto bytes = make_image({.fw_major = 2, .fw_minor = 3, .fw_patch = 4});
  const FirmwareImage img = read_image(file("fw.bin", bytes));
  EXPECT_EQ(img.container, "bin");
  EXPECT_EQ(img.board(), "stm32g474");
  EXPECT_EQ(img.firmware_version(), "2.3.4");
  EXPECT_EQ(img.protocol_version(), proto::version_text(proto::kProtocolMajor, proto::kProtocolMinor));
  EXPECT_EQ(img.address, 0x08000000u);
  EXPECT_EQ(img.bytes, bytes);
}

TEST_F(FlashImage, OneFlippedByteIsRefusedAsCorruptNamingBothCrcs) {
  auto bytes = make_image();
  std::uint32_t stored;
  std::memcpy(&stored, bytes.data() + proto::kImageMetadataOffset + proto::kImageCrcFieldOffset, 4);
  bytes[5000] ^= 0x01;
  const std::uint32_t actual = proto::image_crc32(bytes.data(), bytes.size());
  ASSERT_NE(actual, stored);
  const std::string p = file("fw.bin", bytes);
  EXPECT_EQ(refusal(p), p + ": CRC mismatch: the metadata says " + proto::hash_text(stored) +
                            ", the image's bytes give " + proto::hash_text(actual) +
                            ": the image is corrupt");
}

TEST_F(FlashImage, ATruncatedImageIsRefusedWithBothSizes) {
  auto bytes = make_image();
  bytes.resize(5000);
  const std::string p = file("fw.bin", bytes);
  EXPECT_EQ(refusal(p), p + ": size mismatch: the metadata says 6000 bytes, the image has 5000: it "
                            "is truncated or has bytes added");
}

TEST_F(FlashImage, AnImageOfAnotherProtocolMajorIsRefusedSayingWhy) {
  const std::string p = file("fw.bin", make_image({.protocol_major = proto::kProtocolMajor + 1,
                                                    .protocol_minor = 0}));
  const std::string ours = proto::version_text(proto::kProtocolMajor, proto::kProtocolMinor);
  EXPECT_EQ(refusal(p), p + ": the image speaks protocol " + std::to_string(proto::kProtocolMajor + 1) +
                            ".0, this palp SDK " + sdk_version() + " speaks " + ours +
                            ": the major versions differ. This palpctl could not talk to the "
                            "device after the update: flash with the palpctl built with the image "
                            "(or dfu-util, see firmware/README.md)");
}

TEST_F(FlashImage, AnOlderMinorOfTheSameMajorIsAccepted) {
  if (proto::kProtocolMajor == 0 || proto::kProtocolMinor == 0) GTEST_SKIP() << "no older minor";
  EXPECT_NO_THROW(read_image(file("fw.bin", make_image({.protocol_minor = proto::kProtocolMinor - 1,
                                                         .schema_hash = 0x1234}))));
}

TEST_F(FlashImage, AnUnknownBoardNumberIsRefused) {
  const std::string p = file("fw.bin", make_image({.board = static_cast<proto::BoardId>(77)}));
  EXPECT_EQ(refusal(p), p + ": the image is for board number 77, which this palp does not know: use "
                            "the palp release that built it");
}

TEST_F(FlashImage, AnImageReachingTheCalibrationPagesIsRefused) {
  const std::string p = file("fw.bin", make_image({.size = 0x7F000 + 8}));
  EXPECT_EQ(refusal(p), p + ": the image's 520200 bytes from 0x08000000 reach the calibration's "
                            "flash at 0x0807f000: it is not a firmware image for this board");
  EXPECT_NO_THROW(read_image(file("fits.bin", make_image({.size = 0x7F000}))));
}

TEST_F(FlashImage, AFileWithoutMetadataIsNotAPalpImage) {
  const std::string p = file("other.bin", std::vector<std::uint8_t>(4096, 0xAB));
  EXPECT_EQ(refusal(p), p + ": not a palp firmware image: no \"palp-img\" metadata block at offset "
                            "0x00000400");
}

TEST_F(FlashImage, TheBoardCheckNamesBothBoardsAndTheDevice) {
  const FirmwareImage img = read_image(file("fw.bin", make_image()));
  DeviceInfo sim;
  sim.serial = "SIM-0001";
  sim.board = "palp-sim";
  EXPECT_EQ(board_mismatch(img, sim),
            img.path + ": the image is for board stm32g474, device SIM-0001 is a palp-sim: nothing "
                       "was changed; flash an image built for palp-sim");
  sim.board = "stm32g474";
  EXPECT_EQ(board_mismatch(img, sim), "");
}

TEST_F(FlashImage, TheRecoveryTextNamesTheRealFileInBothCommands) {
  FirmwareImage img = read_image(file("palp-probe-controller.bin", make_image()));
  EXPECT_EQ(recovery_text(img),
            "The device waits in its ROM DFU bootloader (USB 0483:df11) until an image is written; "
            "its calibration pages were not erased. Recover with\n  palpctl flash --device-in-dfu " +
                img.path + "\nor with dfu-util:\n  dfu-util -a 0 -s 0x08000000:leave -D " + img.path);
  img.container = "DfuSe";
  img.path = "/fw/palp-probe-controller.dfu";
  EXPECT_NE(recovery_text(img).find("\n  dfu-util -a 0 -s :leave -D /fw/palp-probe-controller.dfu"),
            std::string::npos);
  img.container = "ELF";
  img.path = "/fw/palp-probe-controller.elf";
  EXPECT_NE(recovery_text(img).find("\n  dfu-util -a 0 -s 0x08000000:leave -D "
                                    "/fw/palp-probe-controller.bin (the .bin the build wrote beside "
                                    "the .elf)"),
            std::string::npos);
  EXPECT_NE(recovery_text(img, true).find("its calibration was erased too (mass erase)"),
            std::string::npos);
}

TEST_F(FlashImage, TheCalibrationFileNeverReplacesAFilePalpDidNotWrite) {
  const std::string path = detail::default_calibration_path((dir_ / "fw.bin").string(), "SN/1 2");
  EXPECT_EQ(path, (dir_ / "fw.bin").string() + ".calibration-SN_1_2.json");
  Calibration c{};
  c.current_offset_A = 0.0125f;
  DeviceInfo d;
  d.serial = "SN/1 2";
  detail::write_calibration_file(path, c, d, "fw.bin");
  EXPECT_NO_THROW(detail::check_calibration_path(path));  // palp's own: may be replaced
  detail::write_calibration_file(path, c, d, "fw.bin");

  const std::string foreign = (dir_ / "notes.json").string();
  std::ofstream(foreign) << "{\"mine\": true}\n";
  try {
    detail::write_calibration_file(foreign, c, d, "fw.bin");
    FAIL() << "a foreign file was replaced";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              foreign + " exists and palp did not write it: nothing was changed; move it away or "
                        "name another file for the calibration (--calibration-file)");
  }
  std::ifstream in(foreign);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "{\"mine\": true}\n");
}

}  // namespace
}  // namespace palp::flash
