// SPDX-License-Identifier: Apache-2.0
// palpctl flash against a real palp-sim, up to the bootloader (the DFU half runs against the ROM
// model in tests/host/sim/test_flash_update.cpp): a wrong board, a corrupt image or an image of
// another protocol major is refused with its exact message and the device untouched (palp-sim's
// status: no frame sent, or no EnterBootloader acknowledged, and it serves the next client as
// before); --dry-run's plan, exact; the calibration read and kept before EnterBootloader.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "firmware_image.hpp"
#include "palp/protocol/verdict_text.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class PalpctlFlash : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("palpctl-flash-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    image_ = (dir_ / "palp-probe-controller.bin").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string image(const palp::test::ImageSpec& spec = {}) {
    palp::test::write_file(image_, palp::test::make_image(spec));
    return image_;
  }
  static ProcessResult run(SimServer& sim, std::vector<std::string> args) {
    EXPECT_TRUE(sim.wait_no_client());
    args.insert(args.begin(), {"--uri", sim.uri()});
    return palpctl(args);
  }
  static std::string field(const std::string& status, const std::string& key) {
    const auto at = status.find(" " + key + "=");
    if (at == std::string::npos) return "(absent)";
    const auto from = at + key.size() + 2;
    return status.substr(from, status.find(' ', from) - from);
  }
  /// The device answers a new client as before: info works, and it is idle.
  static void expect_untouched(SimServer& sim) {
    const std::string st = sim.control("status");
    EXPECT_EQ(field(st, "bootloader_requested"), "0") << st;
    const auto info = run(sim, {"info", "--json"});
    ASSERT_EQ(info.code, 0) << info.err;
    EXPECT_EQ(json::parse(info.out)["status"]["state"], "idle");
  }

  fs::path dir_;
  std::string image_;
};

TEST_F(PalpctlFlash, AnImageForAnotherBoardIsRefusedAfterGetDeviceInfoAndNothingElse) {
  SimServer sim;  // board palp-sim
  ASSERT_TRUE(sim.ok());
  const auto r = run(sim, {"flash", image()});
  EXPECT_EQ(r.code, 2);
  const std::string last = r.err.substr(r.err.rfind("palpctl: "));
  EXPECT_EQ(last, "palpctl: " + image_ + ": the image is for board stm32g474, device SIM-0001 is a "
                  "palp-sim: nothing was changed; flash an image built for palp-sim\n");
  EXPECT_NE(r.err.find("flash: device SIM-0001 at " + sim.uri() + ": board palp-sim"), std::string::npos);
  EXPECT_EQ(field(sim.control("status"), "frames_out"), "1") << "one frame: the DeviceInfo reply";
  expect_untouched(sim);
}

TEST_F(PalpctlFlash, ACorruptImageIsRefusedBeforeTheDeviceIsContacted) {
  SimServer sim({"--board", "stm32g474"});
  ASSERT_TRUE(sim.ok());
  auto bytes = palp::test::make_image();
  std::uint32_t stored;
  std::memcpy(&stored, bytes.data() + palp::proto::kImageMetadataOffset + palp::proto::kImageCrcFieldOffset, 4);
  bytes[3000] ^= 0x40;
  palp::test::write_file(image_, bytes);
  const auto r = run(sim, {"flash", image_});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + image_ + ": CRC mismatch: the metadata says " +
                       palp::proto::hash_text(stored) + ", the image's bytes give " +
                       palp::proto::hash_text(palp::proto::image_crc32(bytes.data(), bytes.size())) +
                       ": the image is corrupt\n");
  EXPECT_EQ(field(sim.control("status"), "frames_out"), "0");
  expect_untouched(sim);
}

TEST_F(PalpctlFlash, AnImageOfAnotherProtocolMajorIsRefusedBeforeTheDeviceIsContacted) {
  SimServer sim({"--board", "stm32g474"});
  ASSERT_TRUE(sim.ok());
  const auto r = run(sim, {"flash", image({.protocol_major = palp::proto::kProtocolMajor + 1,
                                           .protocol_minor = 0})});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + image_ + ": the image speaks protocol " +
                       std::to_string(palp::proto::kProtocolMajor + 1) + ".0, this palp SDK " +
                       palp::sdk_version() + " speaks " +
                       palp::proto::version_text(palp::proto::kProtocolMajor, palp::proto::kProtocolMinor) +
                       ": the major versions differ. This palpctl could not talk to the device "
                       "after the update: flash with the palpctl built with the image (or dfu-util, "
                       "see firmware/README.md)\n");
  EXPECT_EQ(field(sim.control("status"), "frames_out"), "0");
  expect_untouched(sim);
}

TEST_F(PalpctlFlash, DryRunPrintsEveryStepExactlyAndSendsOnlyGetDeviceInfo) {
  SimServer sim({"--board", "stm32g474", "--serial", "G474-0042"});
  ASSERT_TRUE(sim.ok());
  const auto info = run(sim, {"info", "--json"});
  ASSERT_EQ(info.code, 0) << info.err;
  const std::string git = json::parse(info.out)["device"]["git_hash"];
  const std::string frames_before = field(sim.control("status"), "frames_out");
  const std::string path = image();
  const auto bytes = palp::test::make_image();
  std::uint32_t crc;
  std::memcpy(&crc, bytes.data() + palp::proto::kImageMetadataOffset + palp::proto::kImageCrcFieldOffset, 4);
  const std::string proto = palp::proto::version_text(palp::proto::kProtocolMajor, palp::proto::kProtocolMinor);

  const auto r = run(sim, {"flash", "--dry-run", path});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out,
            "flash: image " + path + " (bin): board stm32g474, firmware 0.1.0, protocol " + proto +
                ", 6000 bytes for 0x08000000, size and CRC-32 " + palp::proto::hash_text(crc) +
                " check out\n"
                "flash: device G474-0042 at " + sim.uri() + ": board stm32g474, firmware 0.1.0 (git " +
                git + "), protocol " + proto + "\n"
                "flash: calibration: read it (GetCalibration), keep it in memory and in " + path +
                ".calibration-G474-0042.json\n"
                "flash: bootloader: stop any program (0 A), then EnterBootloader\n"
                "flash: dfu: wait up to 10 s for the ROM DFU device (USB 0483:df11)\n"
                "flash: erase: the pages under 0x08000000..0x08001770 only; the calibration's "
                "pages 0x0807f000..0x08080000 are kept\n"
                "flash: download: 6000 bytes to 0x08000000\n"
                "flash: verify: read the 6000 bytes back and compare\n"
                "flash: leave: start the new firmware at 0x08000000\n"
                "flash: confirm: wait up to 15 s for the controller at " + sim.uri() +
                ", check board stm32g474 and firmware 0.1.0, compare its calibration with the kept "
                "one and write that back if they differ\n"
                "flash: dry run: nothing was sent to the device but GetDeviceInfo\n");
  const std::string st = sim.control("status");
  EXPECT_EQ(std::stoull(field(st, "frames_out")), std::stoull(frames_before) + 1)
      << "one reply: DeviceInfo";
  EXPECT_FALSE(fs::exists(path + ".calibration-G474-0042.json"));
  expect_untouched(sim);
}

TEST_F(PalpctlFlash, ARealRunReadsAndKeepsTheCalibrationThenEntersTheBootloader) {
  SimServer sim({"--board", "stm32g474", "--serial", "G474-0042"});
  ASSERT_TRUE(sim.ok());
  const std::string path = image();
  // no DFU device appears (no ROM bootloader on this machine): the update stops there, having
  // erased nothing, and says how to go on
  const auto r = run(sim, {"flash", "--dfu-wait-s", "0.2", path});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("\nThe controller acknowledged EnterBootloader; nothing was erased. "
                       "Power-cycle it to start its old firmware, or run palpctl flash "
                       "--device-in-dfu " + path + " while it waits in DFU mode.\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(field(sim.control("status"), "bootloader_requested"), "1");
  std::ifstream in(path + ".calibration-G474-0042.json");
  ASSERT_TRUE(in) << "the kept calibration's file";
  const json j = json::parse(in);
  EXPECT_EQ(j["palp_file"], "flash-calibration");
  EXPECT_EQ(j["device"]["serial"], "G474-0042");
  EXPECT_DOUBLE_EQ(j["calibration"]["spring_k_N_per_mm"].get<double>(), 0.0439);
  EXPECT_FALSE(j["calibration_payload_hex"].get<std::string>().empty());
}

TEST_F(PalpctlFlash, AForeignFileWhereTheCalibrationGoesIsRefusedBeforeTheBootloader) {
  SimServer sim({"--board", "stm32g474", "--serial", "G474-0042"});
  ASSERT_TRUE(sim.ok());
  const std::string path = image();
  const std::string mine = (dir_ / "notes.json").string();
  std::ofstream(mine) << "keep me\n";
  const auto r = run(sim, {"flash", "--calibration-file", mine, path});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.substr(r.err.rfind("palpctl: ")),
            "palpctl: " + mine + " exists and palp did not write it: nothing was changed; move it "
                                 "away or name another file for the calibration (--calibration-file)\n");
  expect_untouched(sim);
}

}  // namespace
}  // namespace palpctl::test
