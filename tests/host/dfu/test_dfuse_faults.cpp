// SPDX-License-Identifier: Apache-2.0
// The DfuSe client against injected faults of the ROM-bootloader model: each gives the exact
// message the user sees and leaves the device in the stated state.
#include <gtest/gtest.h>

#include <algorithm>

#include "dfu_fixture.hpp"

namespace palp::dfutest {
namespace {

using Kind = DfuseError::Kind;

const std::string kFlashAgain =
    "flash the image again (palpctl flash IMAGE, or dfu-util -d 0483:df11 -a 0 -s "
    "0x08000000:leave -D IMAGE.bin)";
const std::string kIncomplete =
    "The image in flash is incomplete and will not start: " + kFlashAgain;
const std::string kHoldBoot0 =
    "to reach the bootloader again, hold BOOT0 high while resetting the board";

class DfuFaults : public DfuRig {
 protected:
  std::vector<std::uint8_t> image = test_image(8192);  // 4 pages, 4 blocks
  void flash(dfu::DfuseDevice& d) {
    d.erase_pages(kBase, image.size(), {});
    d.download(kBase, image, {});
  }
  bool erased(std::uint32_t address, std::size_t size) {
    return std::all_of(rom.at(address), rom.at(address) + size,
                       [](std::uint8_t b) { return b == 0xFF; });
  }
};

TEST_F(DfuFaults, ErrWriteOnAPageStopsTheDownloadThereAndIsClearedToDfuIdle) {
  rom.faults.write_error_page = 0x08000800;
  dfu::DfuseDevice d = open();
  const DfuseError e = error_of([&] { flash(d); });
  EXPECT_EQ(std::string(e.what()),
            "writing 2048 bytes at 0x08000800 failed: the device reported errWRITE in dfuERROR "
            "(the flash could not be written). The error was cleared (CLRSTATUS): the device is "
            "in dfuIDLE. " + kIncomplete);
  EXPECT_EQ(e.kind(), Kind::device_status);
  EXPECT_EQ(e.address(), 0x08000800u);
  EXPECT_EQ(e.state(), 10);   // dfuERROR
  EXPECT_EQ(e.status(), 3);   // errWRITE
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
  EXPECT_EQ(rom.status(), DfuStatus::OK);
  EXPECT_TRUE(std::equal(image.begin(), image.begin() + 2048, rom.at(kBase)));
  EXPECT_TRUE(erased(0x08000800, 3 * 2048));  // nothing after the failed block was written
  EXPECT_EQ(rom.illegal_requests, 0);
}

TEST_F(DfuFaults, ErrVerifyIsReportedWithItsAddressAndClearedToDfuIdle) {
  rom.faults.verify_error_page = 0x08001000;
  dfu::DfuseDevice d = open();
  const DfuseError e = error_of([&] { flash(d); });
  EXPECT_EQ(std::string(e.what()),
            "writing 2048 bytes at 0x08001000 failed: the device reported errVERIFY in dfuERROR "
            "(the programmed memory failed verification). The error was cleared (CLRSTATUS): the "
            "device is in dfuIDLE. " + kIncomplete);
  EXPECT_EQ(e.status(), 7);
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
}

TEST_F(DfuFaults, ProgrammingWithoutEraseIsErrCheckErased) {
  std::fill_n(rom.at(kBase), 16, 0x00);
  dfu::DfuseDevice d = open();
  const DfuseError e = error_of([&] { d.download(kBase, image, {}); });
  EXPECT_EQ(std::string(e.what()),
            "writing 2048 bytes at 0x08000000 failed: the device reported errCHECK_ERASED in "
            "dfuERROR (the memory was not erased before programming). The error was cleared "
            "(CLRSTATUS): the device is in dfuIDLE. " + kIncomplete);
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
}

TEST_F(DfuFaults, StalledDnloadReportsTheStallAndTheStatusAndIsClearedToDfuIdle) {
  dfu::DfuseDevice d = open();
  d.erase_pages(kBase, image.size(), {});
  rom.faults.stall_request = 1;  // the next DNLOAD: SET_ADDRESS_POINTER of the first block
  const DfuseError e = error_of([&] { d.download(kBase, image, {}); });
  EXPECT_EQ(std::string(e.what()),
            "writing 2048 bytes at 0x08000000 (setting the address pointer) failed: the device "
            "stalled the request (LIBUSB_ERROR_PIPE) and reports errSTALLEDPKT in dfuERROR (the "
            "device stalled an unexpected request). The error was cleared (CLRSTATUS): the device "
            "is in dfuIDLE. " + kIncomplete);
  EXPECT_EQ(e.kind(), Kind::stalled);
  EXPECT_EQ(e.usb_error(), -9);
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
  EXPECT_TRUE(erased(kBase, image.size()));
}

TEST_F(DfuFaults, ALostBlockTimesOutAndTheDeviceIsAbortedToDfuIdle) {
  dfu::DfuseDevice d = open();
  d.erase_pages(kBase, image.size(), {});
  rom.faults.lose_request = 1;  // DNLOAD: the first block's SET_ADDRESS_POINTER goes through,
  rom.faults.lose_skip = 1;     // its data is lost (the device stays in dfuDNLOAD-IDLE)
  const DfuseError e = error_of([&] { d.download(kBase, image, {}); });
  EXPECT_EQ(std::string(e.what()),
            "writing 2048 bytes at 0x08000000 failed: no answer within 5000 ms "
            "(LIBUSB_ERROR_TIMEOUT). Aborted (ABORT): the device is in dfuIDLE. " + kIncomplete);
  EXPECT_EQ(e.kind(), Kind::timeout);
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
}

TEST_F(DfuFaults, StalledUploadSaysNothingWasChanged) {
  dfu::DfuseDevice d = open();
  rom.faults.stall_request = 2;
  const DfuseError e = error_of([&] { d.upload(kBase, 4096, {}); });
  EXPECT_EQ(std::string(e.what()),
            "reading 2048 bytes at 0x08000000 failed: the device stalled the request "
            "(LIBUSB_ERROR_PIPE) and reports errSTALLEDPKT in dfuERROR (the device stalled an "
            "unexpected request). The error was cleared (CLRSTATUS): the device is in dfuIDLE. "
            "Nothing was changed by reading: read it back again; if this repeats, flash the image "
            "again");
  EXPECT_EQ(rom.state(), DfuState::dfuIDLE);
}

TEST_F(DfuFaults, AGetStatusStalledWhileBusyIsAskedAgainAndTheFlashSucceeds) {
  rom.faults.stall_keeps_state = true;
  dfu::DfuseDevice d = open();
  rom.faults.stall_request = 3;  // the first erase's first GETSTATUS
  flash(d);
  EXPECT_TRUE(std::equal(image.begin(), image.end(), rom.at(kBase)));
  EXPECT_EQ(rom.early_polls, 0);
}

TEST_F(DfuFaults, UnplugMidDownloadSaysSoAndWhereAndHowToRecover) {
  rom.faults.unplug_after = 28;  // open 1, erase 4 x 3 + ABORT, 2 blocks x 6, then the 3rd block
  dfu::DfuseDevice d = open();
  const DfuseError e = error_of([&] { flash(d); });
  EXPECT_EQ(std::string(e.what()),
            "writing 2048 bytes at 0x08001000 (setting the address pointer) failed: the device "
            "was unplugged (LIBUSB_ERROR_NO_DEVICE). Plug it back in (" + kHoldBoot0 + "). " +
            kIncomplete);
  EXPECT_EQ(e.kind(), Kind::unplugged);
  EXPECT_EQ(e.address(), 0x08001000u);
  EXPECT_EQ(e.usb_error(), -4);
  EXPECT_TRUE(rom.unplugged);
}

TEST_F(DfuFaults, SlowBwPollTimeoutIsWaitedOutBeforeEachStatusRequest) {
  rom.erase_poll_ms = 1500;
  dfu::DfuseDevice d = open();
  d.erase_pages(kBase, image.size(), {});
  EXPECT_EQ(rom.early_polls, 0);
  EXPECT_GE(slept_ms, 4u * 1500);
  EXPECT_LT(slept_ms, 4u * 1500 + 4 * 10);  // and not much more: the wait is what was asked
  EXPECT_EQ(rom.erased_pages.size(), 4u);
}

TEST_F(DfuFaults, ADeviceStuckBusyIsGivenUpAfterTheBusyLimit) {
  rom.faults.stuck_busy = true;
  dfu::DfuseDevice d = open();
  const DfuseError e = error_of([&] { flash(d); });
  EXPECT_EQ(std::string(e.what()),
            "erasing the page at 0x08000000 failed: the device stayed busy (dfuDNBUSY) longer "
            "than 30000 ms; unplug it and put it back in DFU mode (" + kHoldBoot0 + "). The "
            "image's pages may be partly erased, so the application may not start: " +
            kFlashAgain);
  EXPECT_EQ(e.kind(), Kind::timeout);
  EXPECT_LE(slept_ms, 30000u);
  EXPECT_GE(slept_ms, 30000u - 25);
  EXPECT_EQ(rom.state(), DfuState::dfuDNBUSY);  // left busy: only a reset helps
}

TEST_F(DfuFaults, EveryControlTransferHasABoundedTimeout) {
  dfu::DfuseDevice d = open();
  flash(d);
  (void)d.upload(kBase, image.size(), {});
  EXPECT_EQ(bus->zero_timeouts, 0);
  EXPECT_EQ(bus->max_timeout_ms, 5000u);
}

TEST_F(DfuFaults, LeaveToleratesTheDeviceResettingBeforeItAnswers) {
  dfu::DfuseDevice d = open();
  rom.faults.unplug_after = rom.transfers + 3 + 1;  // SET_ADDRESS (3), the zero DNLOAD, then gone
  d.leave(kBase);
  EXPECT_TRUE(rom.unplugged);
  EXPECT_EQ(bus->calls.back(), "exit");
}

TEST_F(DfuFaults, UnplugWhileOpeningSaysSo) {
  rom.faults.unplug_after = 0;
  const DfuseError e = error_of([&] { open(); });
  EXPECT_EQ(std::string(e.what()),
            "bringing the DFU device 0483:df11 to dfuIDLE failed: the device was unplugged "
            "(LIBUSB_ERROR_NO_DEVICE). Plug it back in (" + kHoldBoot0 + "). Then try again");
  EXPECT_EQ(bus->calls.back(), "exit");
}

}  // namespace
}  // namespace palp::dfutest
