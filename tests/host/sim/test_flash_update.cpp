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

}  // namespace
}  // namespace palp::flash
