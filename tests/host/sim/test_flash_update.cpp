// SPDX-License-Identifier: Apache-2.0
// palp::flash::update end to end without hardware: the application is palp-sim linked in, posing
// as an stm32g474 (sim+inproc board=), and the ROM bootloader is dfuclient's model of it behind
// the UsbApi seam (tests/host/dfu/dfu_device_model.hpp), in virtual time. The controller
// "leaves" for the bootloader when the simulator has acknowledged EnterBootloader (its status
// says bootloader_requested=1) and "comes back" once the model has left DFU.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "../dfu/dfu_device_model.hpp"
#include "../unit/firmware_image.hpp"
#include "palp/error.hpp"
#include "palp/flash.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/sim_inproc.hpp"

namespace palp::flash {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr std::uint32_t kCalibrationPages = 0x0807F000;

class FlashUpdate : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("palp-flash-update-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    image_path_ = (dir_ / "palp-probe-controller.bin").string();
    test::write_file(image_path_, test::make_image());
    // the calibration the device has (committed), and a journal's bytes in the model's flash
    Probe p(sim_.transport());
    kept_ = p.calibration();
    kept_.current_offset_A = 0.0125f;
    kept_.spring_k_N_per_m = 44.5f;
    p.set_calibration(kept_);
    p.commit_calibration();
    p.close();
    for (std::uint32_t k = 0; k < 4096; ++k) rom_.at(kCalibrationPages)[k] = static_cast<std::uint8_t>(k * 5);
    calibration_flash_ = std::vector<std::uint8_t>(rom_.at(kCalibrationPages), rom_.at(kCalibrationPages) + 4096);
    bus_->appears_at_ms = 400;  // the ROM enumerates a moment after the reset
  }
  void TearDown() override { fs::remove_all(dir_); }

  bool in_bootloader() { return sim_.control("status").find(" bootloader_requested=1") != std::string::npos; }

  FlashHooks hooks() {
    FlashHooks h;
    h.say = [this](const std::string& line) { said_.push_back(line); };
    h.usb = bus_;
    h.sleep = [this](std::chrono::milliseconds d) { rom_.advance(static_cast<std::uint64_t>(d.count())); };
    h.open = [this](const std::string&, std::chrono::milliseconds) -> std::unique_ptr<Transport> {
      if (in_bootloader() && !rom_.reset) throw ConnectionError("the controller is in its bootloader");
      if (rom_.reset && after_reset_) {
        after_reset_();
        after_reset_ = nullptr;
      }
      return sim_.transport();
    };
    return h;
  }
  FlashOptions options() {
    FlashOptions o;
    o.uri = "sim+inproc://none?board=stm32g474";
    return o;
  }
  bool calibration_pages_untouched() {
    return std::equal(calibration_flash_.begin(), calibration_flash_.end(), rom_.at(kCalibrationPages));
  }
  Calibration device_calibration() {
    Probe p(sim_.transport());
    return p.calibration();
  }

  sim::InprocSimulator sim_{{.serial = "G474-0042", .board = "stm32g474"}};
  std::shared_ptr<dfumodel::DfuBus> bus_ = std::make_shared<dfumodel::DfuBus>();
  dfumodel::DfuRom& rom_ = bus_->rom;
  fs::path dir_;
  std::string image_path_;
  Calibration kept_{};
  std::vector<std::uint8_t> calibration_flash_;
  std::vector<std::string> said_;
  std::function<void()> after_reset_;
};

TEST_F(FlashUpdate, AnUpdateWritesTheImageAndKeepsTheCalibrationPagesAndTheCalibration) {
  const FirmwareImage image = read_image(image_path_);
  const FlashReport r = update(image, options(), hooks());

  EXPECT_TRUE(std::equal(image.bytes.begin(), image.bytes.end(), rom_.at(0x08000000)));
  EXPECT_EQ(rom_.erased_pages, (std::vector<std::uint32_t>{0x08000000, 0x08000800, 0x08001000}))
      << "the three pages of a 6000-byte image, no other";
  EXPECT_EQ(rom_.mass_erases, 0);
  EXPECT_TRUE(calibration_pages_untouched());
  EXPECT_TRUE(rom_.reset);
  EXPECT_EQ(rom_.started_at, 0x08000000u);

  ASSERT_TRUE(r.calibration);
  EXPECT_EQ(r.calibration->current_offset_A, 0.0125f);
  EXPECT_FALSE(r.calibration_restored);
  const Calibration now = device_calibration();
  EXPECT_EQ(now.current_offset_A, kept_.current_offset_A);
  EXPECT_EQ(now.spring_k_N_per_m, kept_.spring_k_N_per_m);
  ASSERT_TRUE(r.after);
  EXPECT_EQ(r.after->firmware_version, "0.1.0");
  EXPECT_EQ(said_.back(), "calibration: unchanged");

  EXPECT_EQ(r.calibration_file, image_path_ + ".calibration-G474-0042.json");
  std::ifstream in(r.calibration_file);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["palp_file"], "flash-calibration");
  EXPECT_EQ(j["device"]["serial"], "G474-0042");
}

TEST_F(FlashUpdate, ACalibrationLostInTheUpdateIsWrittenBackAndCommitted) {
  after_reset_ = [this] {  // the new firmware came up with its defaults
    Probe p(sim_.transport());
    Calibration c = p.calibration();
    c.current_offset_A = 0.0f;
    c.spring_k_N_per_m = 43.9f;
    p.set_calibration(c);
  };
  const FlashReport r = update(read_image(image_path_), options(), hooks());
  EXPECT_TRUE(r.calibration_restored);
  EXPECT_EQ(said_.back(), "calibration: restored");
  const Calibration now = device_calibration();
  EXPECT_EQ(now.current_offset_A, 0.0125f);
  EXPECT_EQ(now.spring_k_N_per_m, 44.5f);
}

TEST_F(FlashUpdate, AWriteErrorAfterTheEraseThrowsFlashErrorWithTheRecoveryCommands) {
  rom_.faults.write_error_page = 0x08000800;
  const FirmwareImage image = read_image(image_path_);
  try {
    update(image, options(), hooks());
    FAIL() << "no FlashError";
  } catch (const FlashError& e) {
    EXPECT_TRUE(e.erased());
    const std::string m = e.what();
    const std::string tail = "\n" + recovery_text(image);
    ASSERT_GE(m.size(), tail.size());
    EXPECT_EQ(m.substr(m.size() - tail.size()), tail) << m;
    EXPECT_NE(m.find("errWRITE"), std::string::npos) << m;
    EXPECT_NE(m.find("palpctl flash --device-in-dfu " + image_path_), std::string::npos);
    EXPECT_NE(m.find("dfu-util -a 0 -s 0x08000000:leave -D " + image_path_), std::string::npos);
  }
  EXPECT_TRUE(calibration_pages_untouched());
  EXPECT_FALSE(rom_.reset) << "the device stays in DFU, waiting for the image";
}

TEST_F(FlashUpdate, InterruptedInDfuBeforeTheEraseStartsTheOldFirmwareWithNothingErased) {
  FlashHooks h = hooks();
  h.interrupted = [this] { return rom_.transfers > 0; };  // Ctrl-C once the DFU device is open
  const FlashReport r = update(read_image(image_path_), options(), h);
  EXPECT_TRUE(r.interrupted);
  EXPECT_TRUE(rom_.erased_pages.empty());
  EXPECT_TRUE(rom_.reset) << "left DFU: the old application runs again";
  EXPECT_EQ(said_.back(),
            "interrupted before the erase: nothing was erased; the old firmware was started again");
}

TEST_F(FlashUpdate, ADeviceAlreadyInDfuIsFlashedAndItsCalibrationReadAfterwards) {
  FlashOptions o = options();
  o.device_in_dfu = true;
  ASSERT_EQ(sim_.control("status").find(" bootloader_requested=1"), std::string::npos);
  bus_->appears_at_ms = 0;
  const FlashReport r = update(read_image(image_path_), o, hooks());
  EXPECT_TRUE(r.from_dfu);
  EXPECT_FALSE(r.before);
  EXPECT_EQ(rom_.erased_pages.size(), 3u);
  EXPECT_TRUE(calibration_pages_untouched());
  ASSERT_TRUE(r.calibration);
  EXPECT_EQ(r.calibration->current_offset_A, 0.0125f);
  EXPECT_EQ(said_.back(), "calibration: read (nothing kept to compare it with)");
}

TEST_F(FlashUpdate, MassEraseOnlyWhenAskedAndTheCalibrationIsWrittenBackAfterIt) {
  FlashOptions o = options();
  o.mass_erase = true;
  after_reset_ = [this] {  // a mass erase took the calibration journal: defaults
    Probe p(sim_.transport());
    Calibration c = p.calibration();
    c.current_offset_A = 0.0f;
    p.set_calibration(c);
  };
  const FlashReport r = update(read_image(image_path_), o, hooks());
  EXPECT_EQ(rom_.mass_erases, 1);
  EXPECT_TRUE(rom_.erased_pages.empty());
  EXPECT_TRUE(r.calibration_restored);
  EXPECT_EQ(device_calibration().current_offset_A, 0.0125f);
}

/// A controller whose firmware speaks another protocol major: it answers only the frozen
/// requests (GetDeviceInfo, EnterBootloader), in frames of its own major, and records every
/// message it got (in a record that outlives it: the update owns and closes the transport).
struct DeviceRecord {
  std::vector<std::string> got;
  bool entered = false;
};
class OtherMajorDevice final : public Transport {
 public:
  explicit OtherMajorDevice(std::shared_ptr<DeviceRecord> record) : rec_(std::move(record)) {}
  static constexpr proto::u8 kMajor = proto::kProtocolMajor + 1;

  void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds) override {
    reader_.feed_messages(
        bytes.data(), bytes.size(),
        [&](const proto::FrameHeader& h, const auto& m) {
          using M = std::decay_t<decltype(m)>;
          rec_->got.push_back(M::kName);
          if constexpr (std::is_same_v<M, proto::GetDeviceInfo>) {
            proto::DeviceInfo d{};
            d.protocol_major = kMajor;
            d.protocol_minor = 0;
            d.schema_hash = 0x11111111u;
            d.fw_major = 9;
            d.serial.assign("OLD-7");
            d.board.assign("stm32g474");
            d.git_hash.assign("0ld0ld0");
            d.state = proto::DeviceState::incompatible;
            reply(d, h.seq);
          } else if constexpr (std::is_same_v<M, proto::EnterBootloader>) {
            if (m.magic == proto::kBootloaderMagic) rec_->entered = true;
            reply(proto::Ack{static_cast<proto::u8>(proto::MessageId::EnterBootloader)}, h.seq);
          }
        },
        [](proto::Reject) {});
  }
  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds) override {
    const std::size_t n = std::min(buf.size(), out_.size());
    std::copy_n(out_.begin(), n, buf.begin());
    out_.erase(out_.begin(), out_.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }
  std::uint32_t max_device_bytes_per_s() const override { return 1u << 20; }
  const std::string& uri() const override { return uri_; }

 private:
  template <class M>
  void reply(const M& m, std::uint16_t seq) {
    std::vector<std::uint8_t> w(proto::kMaxWireFrame);
    w.resize(proto::encode_message(m, seq, proto::kFlagResponse, w.data(), w.size(), kMajor));
    out_.insert(out_.end(), w.begin(), w.end());
  }
  std::shared_ptr<DeviceRecord> rec_;
  proto::FrameReader reader_;
  std::vector<std::uint8_t> out_;
  std::string uri_ = "usb://OLD-7";
};

TEST_F(FlashUpdate, ADeviceOfAnotherProtocolMajorIsReflashedThroughTheFrozenRequestsAlone) {
  auto old = std::make_shared<DeviceRecord>();
  std::unique_ptr<Transport> old_link = std::make_unique<OtherMajorDevice>(old);
  FlashHooks h = hooks();
  h.open = [&](const std::string&, std::chrono::milliseconds) -> std::unique_ptr<Transport> {
    if (old_link) return std::move(old_link);  // the controller before the update
    if (!rom_.reset) throw ConnectionError("the controller is in its bootloader");
    return sim_.transport();  // the new firmware: palp-sim's, this build's protocol
  };
  const FlashReport r = update(read_image(image_path_), options(), h);
  EXPECT_EQ(old->got, (std::vector<std::string>{"GetDeviceInfo", "EnterBootloader"}))
      << "no Hello, no session: only frozen requests";
  EXPECT_TRUE(old->entered);
  ASSERT_TRUE(r.before);
  EXPECT_EQ(r.before->firmware_version, "9.0.0");
  EXPECT_EQ(rom_.erased_pages.size(), 3u);
  EXPECT_TRUE(calibration_pages_untouched());
  EXPECT_EQ(r.after->firmware_version, "0.1.0");
  EXPECT_TRUE(r.calibration_file.empty());
  EXPECT_NE(std::find(said_.begin(), said_.end(),
                      "calibration: cannot be read: the device speaks protocol " +
                          std::to_string(OtherMajorDevice::kMajor) +
                          ".0, which this SDK cannot talk to; the calibration's pages "
                          "0x0807f000..0x08080000 are kept"),
            said_.end());
}

}  // namespace
}  // namespace palp::flash
