// SPDX-License-Identifier: Apache-2.0
// The SETUP packets the DfuSe client hands to libusb, checked byte for byte against
// usb-dfu-facts.md §5.2/§5.5 with the scripted FakeUsb (independent of the device model).
#include <gtest/gtest.h>

#include "../unit/fake_usb_apis.hpp"
#include "palp/dfu.hpp"

namespace palp::dfutest {
namespace {

std::vector<std::uint8_t> status(std::uint8_t state, std::uint32_t poll_ms = 0) {
  return {0x00, static_cast<std::uint8_t>(poll_ms), static_cast<std::uint8_t>(poll_ms >> 8),
          static_cast<std::uint8_t>(poll_ms >> 16), state, 0};
}

TEST(DfuseRequests, ErasingOnePageSendsTheDfuseEraseCommandAndPollsThenAborts) {
  auto usb = std::make_shared<fakes::FakeUsb>();
  usb->devices.push_back({{0x0483, 0xDF11, 0x2200, 0, 0}, "", "", 0, false});
  usb->interfaces = {{0, 0, 0xFE, 0x01, 0x02, 4, {9, 0x21, 0x0B, 0xFF, 0, 0x00, 0x04, 0x1A, 0x01}}};
  // the fake serves every string index with "" except serial/product: give the layout as product
  usb->devices[0].desc.i_product = 4;
  usb->devices[0].product = "@Internal Flash  /0x08000000/256*02Kg";
  usb->control_in = {{6, status(2)},                // open: GETSTATUS -> dfuIDLE
                     {5, {}},                        // DNLOAD block 0: 41 + address
                     {6, status(4, 20)},             // GETSTATUS -> dfuDNBUSY, 20 ms
                     {6, status(5)},                 // GETSTATUS -> dfuDNLOAD-IDLE
                     {0, {}}};                       // ABORT
  std::vector<std::chrono::milliseconds> sleeps;
  dfu::DfuseOptions o;
  o.sleep = [&](std::chrono::milliseconds d) { sleeps.push_back(d); };
  dfu::DfuseDevice d = dfu::DfuseDevice::open(usb, {}, std::chrono::milliseconds{0}, o);
  EXPECT_EQ(d.transfer_size(), 1024u);  // from the functional descriptor's wTransferSize
  d.erase_pages(0x08000800, 10, {});
  ASSERT_EQ(usb->controls.size(), 5u);
  const auto& c = usb->controls;
  EXPECT_EQ(c[0].request_type, 0xA1);  // IN, class, interface
  EXPECT_EQ(c[0].request, 3);          // GETSTATUS
  EXPECT_EQ(c[0].length, 6);
  EXPECT_EQ(c[1].request_type, 0x21);  // OUT, class, interface
  EXPECT_EQ(c[1].request, 1);          // DNLOAD
  EXPECT_EQ(c[1].value, 0);            // block 0 = DfuSe command
  EXPECT_EQ(c[1].index, 0);            // interface 0
  EXPECT_EQ(c[1].bytes, (std::vector<std::uint8_t>{0x41, 0x00, 0x08, 0x00, 0x08}));
  EXPECT_EQ(c[2].request, 3);
  EXPECT_EQ(c[3].request, 3);
  EXPECT_EQ(c[4].request_type, 0x21);
  EXPECT_EQ(c[4].request, 6);          // ABORT
  EXPECT_EQ(c[4].length, 0);
  ASSERT_EQ(sleeps.size(), 1u);
  EXPECT_EQ(sleeps[0], std::chrono::milliseconds{20});  // bwPollTimeout, 24-bit LE
  for (const auto& t : c) EXPECT_EQ(t.timeout_ms, 5000u);
}

}  // namespace
}  // namespace palp::dfutest
