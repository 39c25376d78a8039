// SPDX-License-Identifier: Apache-2.0
// The DfuSe client against the ROM-bootloader model: opening, erase + download + read-back of an
// image, which pages are erased, addresses refused before any request, leaving DFU.
#include <gtest/gtest.h>

#include <algorithm>

#include "dfu_fixture.hpp"

namespace palp::dfutest {
namespace {

using dfu::Progress;
using std::chrono::milliseconds;


TEST_F(DfuRig, OpenClaimsAlt0AndReadsLayoutTransferSizeAndSerial) {
  dfu::DfuseDevice d = open();
  EXPECT_EQ(d.memory_layout(), "@Internal Flash  /0x08000000/256*02Kg");
  EXPECT_EQ(d.layout().segments.at(0).pages, 256u);
  EXPECT_EQ(d.transfer_size(), 2048u);
  EXPECT_EQ(d.serial(), "206C35A35430");
  EXPECT_NE(std::find(bus->calls.begin(), bus->calls.end(), "claim_interface 0"), bus->calls.end());
  EXPECT_NE(std::find(bus->calls.begin(), bus->calls.end(), "set_interface_alt_setting 0 0"),
            bus->calls.end());
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
  EXPECT_EQ(rom.illegal_requests, 0);
}

TEST_F(DfuRig, OpenWaitsForTheBootloaderToEnumerate) {
  bus->appears_at_ms = 700;
  dfu::DfuseDevice d = open(milliseconds{2000});
  EXPECT_GE(slept_ms, 700u);
  EXPECT_LT(slept_ms, 900u);
}

TEST_F(DfuRig, OpenGivesUpAfterTheWaitSayingHowToEnterTheBootloader) {
  bus->appears_at_ms = 5000;
  const DfuseError e = error_of([&] { open(milliseconds{1000}); });
  EXPECT_EQ(e.kind(), DfuseError::Kind::not_found);
  EXPECT_EQ(std::string(e.what()),
            "no device in DFU mode (0483:df11) found within 1000 ms; put the controller into its "
            "bootloader (palpctl flash does it by EnterBootloader; by hand: hold BOOT0 high while "
            "resetting the board) and check the cable");
  EXPECT_LE(slept_ms, 1100u);
}

TEST_F(DfuRig, OpenRefusesAnotherSerialListingTheOneFound) {
  const DfuseError e = error_of(
      [&] { dfu::DfuseDevice::open(bus, {"OTHER", 0x0483, 0xDF11}, milliseconds{0}, options()); });
  EXPECT_EQ(std::string(e.what()),
            "no device in DFU mode (0483:df11, serial OTHER) found within 0 ms (found: "
            "206C35A35430); put the controller into its bootloader (palpctl flash does it by "
            "EnterBootloader; by hand: hold BOOT0 high while resetting the board) and check the "
            "cable");
}

TEST_F(DfuRig, OpenWithoutPermissionSaysHowToGrantIt) {
  bus->open_error = detail::kUsbErrorAccess;
  const DfuseError e = error_of([&] { open(); });
  EXPECT_EQ(e.kind(), DfuseError::Kind::access);
  EXPECT_EQ(std::string(e.what()),
            "cannot open the DFU device 0483:df11 (LIBUSB_ERROR_ACCESS): install the udev rules "
            "(host/udev/70-palp.rules, e.g. into /etc/udev/rules.d, then `udevadm control "
            "--reload && udevadm trigger` and re-plug) or run as root");
  EXPECT_EQ(rom.transfers, 0);
}

TEST_F(DfuRig, OpenClearsADeviceLeftInDfuErrorByCLRSTATUS) {
  rom.force(DfuState::dfuERROR, DfuStatus::errWRITE);
  dfu::DfuseDevice d = open();
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
  EXPECT_EQ(rom.status(), DfuStatus::OK);
  EXPECT_EQ(rom.illegal_requests, 0);
}

TEST_F(DfuRig, OpenAbortsADeviceLeftInUploadIdle) {
  rom.force(DfuState::dfuUPLOAD_IDLE, DfuStatus::OK);
  dfu::DfuseDevice d = open();
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
  EXPECT_EQ(rom.illegal_requests, 0);
}

TEST_F(DfuRig, EraseDownloadUploadGivesTheImageBackAndPadsTheTailWithErasedBytes) {
  const auto image = test_image(10001);  // 5 blocks, the last not a multiple of 8
  dfu::DfuseDevice d = open();
  d.erase_pages(kBase, image.size(), record());
  d.download(kBase, image, record());
  const auto back = d.upload(kBase, image.size(), record());
  EXPECT_EQ(back, image);
  EXPECT_TRUE(std::equal(image.begin(), image.end(), rom.at(kBase)));
  EXPECT_EQ(*rom.at(kBase + 10001), 0xFF);  // the padding of the last double word
  EXPECT_EQ(rom.illegal_requests, 0);
  EXPECT_EQ(rom.early_polls, 0);          // every bwPollTimeout was honoured
  EXPECT_EQ(bus->zero_timeouts, 0);
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
  EXPECT_EQ(rom.mass_erases, 0);
}

TEST_F(DfuRig, ProgressCountsPagesThenBlocksThenReadBackBlocks) {
  const auto image = test_image(5000);
  dfu::DfuseDevice d = open();
  d.erase_pages(kBase, image.size(), record());
  d.download(kBase, image, record());
  (void)d.upload(kBase, image.size(), record());
  ASSERT_EQ(progress.size(), 3u + 3u + 3u);
  EXPECT_EQ(progress[0].phase, Progress::Phase::erase);
  EXPECT_EQ(progress[0].done, 2048u);
  EXPECT_EQ(progress[2].done, 6144u);
  EXPECT_EQ(progress[2].total, 6144u);
  EXPECT_EQ(progress[3].phase, Progress::Phase::download);
  EXPECT_EQ(progress[4].done, 4096u);
  EXPECT_EQ(progress[5].done, 5000u);
  EXPECT_EQ(progress[5].total, 5000u);
  EXPECT_EQ(progress[8].phase, Progress::Phase::verify);
  EXPECT_EQ(progress[8].done, 5000u);
}

TEST_F(DfuRig, OnlyTheImagesPagesAreErasedAndTheCalibrationKeepsItsBytes) {
  std::fill_n(rom.at(kCalibration), 4096, 0xC5);
  std::fill_n(rom.at(0x08040000), 2048, 0x3C);  // bank 2's first page
  std::fill_n(rom.at(kBase), 64 * 1024, 0x00);  // an old image
  const auto image = test_image(20000);         // 10 pages
  dfu::DfuseDevice d = open();
  d.erase_pages(kBase, image.size(), {});
  d.download(kBase, image, {});
  ASSERT_EQ(rom.erased_pages.size(), 10u);
  for (std::uint32_t k = 0; k < 10; ++k) EXPECT_EQ(rom.erased_pages[k], kBase + k * 2048);
  EXPECT_TRUE(std::all_of(rom.at(kCalibration), rom.at(kCalibration) + 4096,
                          [](std::uint8_t b) { return b == 0xC5; }));
  EXPECT_EQ(*rom.at(0x08040000), 0x3C);
  EXPECT_EQ(*rom.at(kBase + 10 * 2048), 0x00);  // the old image's 11th page: not touched
  EXPECT_EQ(rom.mass_erases, 0);
}

TEST_F(DfuRig, MassEraseHappensOnlyWhenAskedAndErasesEverything) {
  std::fill_n(rom.at(kCalibration), 4096, 0xC5);
  dfu::DfuseDevice d = open();
  d.mass_erase(record());
  EXPECT_EQ(rom.mass_erases, 1);
  EXPECT_EQ(*rom.at(kCalibration), 0xFF);
  ASSERT_EQ(progress.size(), 1u);
  EXPECT_EQ(progress[0].done, 512u * 1024);
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
}

TEST_F(DfuRig, AddressesOutsideTheLayoutAreRefusedBeforeAnyRequest) {
  dfu::DfuseDevice d = open();
  const int before = rom.transfers;
  const auto image = test_image(4096);
  EXPECT_EQ(error_of([&] { d.erase_pages(0x0807F800, 4096, {}); }).kind(),
            DfuseError::Kind::refused_address);
  EXPECT_EQ(error_of([&] { d.download(0x0807F800, image, {}); }).kind(),
            DfuseError::Kind::refused_address);
  EXPECT_EQ(error_of([&] { d.upload(0x07FFFFFF, 16, {}); }).kind(),
            DfuseError::Kind::refused_address);
  const DfuseError leave = error_of([&] { d.leave(0x20000000); });
  EXPECT_EQ(std::string(leave.what()),
            "starting the application at 0x20000000 refused before anything was sent: the address "
            "is outside the device's memory layout \"Internal Flash\"");
  const DfuseError odd = error_of([&] { d.download(kBase + 4, image, {}); });
  EXPECT_EQ(std::string(odd.what()),
            "downloading to 0x08000004 refused before anything was sent: the STM32G474 programs "
            "8-byte double words, the address must be a multiple of 8");
  EXPECT_EQ(rom.transfers, before);
  EXPECT_EQ(rom.erased_pages.size(), 0u);
}

TEST_F(DfuRig, LeaveStartsTheApplicationAtTheAddressAndClosesTheDevice) {
  const auto image = test_image(4096);
  dfu::DfuseDevice d = open();
  d.erase_pages(kBase, image.size(), {});
  d.download(kBase, image, {});
  d.leave(kBase, record());
  EXPECT_TRUE(rom.reset);
  EXPECT_EQ(rom.state(), DfuState::dfuMANIFEST_WAIT_RESET);
  ASSERT_EQ(progress.size(), 1u);
  EXPECT_EQ(progress[0].phase, Progress::Phase::manifest);
  EXPECT_EQ(rom.started_at, kBase);
  EXPECT_EQ(rom.illegal_requests, 0);
  EXPECT_EQ(std::string(error_of([&] { d.upload(kBase, 16, {}); }).what()),
            "the DFU device was closed (it left DFU mode): open it again");
  EXPECT_EQ(bus->calls.back(), "exit");
}

}  // namespace
}  // namespace palp::dfutest
