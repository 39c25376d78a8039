// SPDX-License-Identifier: Apache-2.0
// Discovery: the real enumeration on this machine (no palp controller here, perhaps no USB at
// all) is an empty list, never an error; through fakes, the USB and HID views of a controller
// merge into one listing with both URIs and the firmware version from bcdDevice, and a
// controller that cannot be opened is listed with a note that says what to do.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "fake_usb_apis.hpp"
#include "palp/discovery.hpp"
#include "palp/error.hpp"
#include "transport/usb_api.hpp"

namespace palp {
namespace {

using fakes::FakeHid;
using fakes::FakeUsb;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(Discovery, RealEnumerationFindsNoControllerAndDoesNotThrow) {
  std::vector<DeviceListing> found;
  ASSERT_NO_THROW(found = list_devices());
  EXPECT_TRUE(found.empty());
}

TEST(Discovery, OneControllerOnBothInterfacesIsOneListingWithTwoUris) {
  FakeUsb usb;
  usb.devices.push_back({FakeUsb::desc(0x0102), "PALP-0042", "palp probe controller"});
  FakeHid hid;
  hid.devices.push_back(FakeHid::info("PALP-0042", 0x0102));
  const auto found = detail::list_devices_with(DiscoveryOptions{}, &usb, &hid);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].serial, "PALP-0042");
  EXPECT_EQ(found[0].firmware_version, "1.2");
  EXPECT_EQ(found[0].product, "palp probe controller");
  EXPECT_EQ(found[0].vid, 0x1209);
  EXPECT_EQ(found[0].pid, 0x0001);
  EXPECT_THAT(found[0].uris, ElementsAre("usb://PALP-0042", "hid://PALP-0042"));
  EXPECT_EQ(found[0].note, "");
  // Every device it opened, it closed; the context is gone.
  EXPECT_THAT(usb.calls, ElementsAre("init", "get_device_list", "open 0", "close 0",
                                     "free_device_list", "exit"));
}

TEST(Discovery, ControllersAreListedBySerialWithTheirOwnTransports) {
  FakeUsb usb;
  usb.devices.push_back({FakeUsb::desc(0x1234), "B-2", "p"});
  usb.devices.push_back({FakeUsb::desc(0x0102, 0x1209, 0x0002), "NOT-PALP", "x"});
  FakeHid hid;
  hid.devices.push_back(FakeHid::info("A-1", 0x0013));
  const auto found = detail::list_devices_with(DiscoveryOptions{}, &usb, &hid);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].serial, "A-1");
  EXPECT_EQ(found[0].firmware_version, "0.13");
  EXPECT_THAT(found[0].uris, ElementsAre("hid://A-1"));
  EXPECT_EQ(found[1].serial, "B-2");
  EXPECT_EQ(found[1].firmware_version, "12.34");
  EXPECT_THAT(found[1].uris, ElementsAre("usb://B-2"));
}

TEST(Discovery, AControllerThatCannotBeOpenedHasANote) {
  FakeUsb usb;
  usb.devices.push_back({FakeUsb::desc(0x0102), "PALP-0042", ""});
  usb.devices[0].open_error = detail::kUsbErrorAccess;
  FakeHid hid;
  hid.devices.push_back(FakeHid::info("PALP-0042", 0x0102));
  hid.open_error = "Failed to open a device with path '/dev/hidraw0': Permission denied";
  const auto found = detail::list_devices_with(DiscoveryOptions{}, &usb, &hid);
  ASSERT_EQ(found.size(), 1u);  // hidapi read the serial; merged with the USB view
  EXPECT_EQ(found[0].serial, "PALP-0042");
  EXPECT_EQ(found[0].firmware_version, "1.2");
  EXPECT_THAT(found[0].uris, ElementsAre("usb://PALP-0042", "hid://PALP-0042"));
  EXPECT_EQ(found[0].note,
            std::string("cannot open over USB: LIBUSB_ERROR_ACCESS (permission denied: ") +
                detail::kPermissionHint +
                "); cannot open over HID: Failed to open a device with path '/dev/hidraw0': "
                "Permission denied (" + detail::kPermissionHint + ")");
}

TEST(Discovery, AnUnreadableUsbControllerAloneIsListedWithoutUris) {
  FakeUsb usb;
  usb.devices.push_back({FakeUsb::desc(0x010A), "PALP-0042", ""});
  usb.devices[0].open_error = detail::kUsbErrorAccess;
  const auto found = detail::list_devices_with(DiscoveryOptions{}, &usb, nullptr);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].serial, "");
  EXPECT_EQ(found[0].firmware_version, "unknown (bcdDevice 0x010a)");
  EXPECT_TRUE(found[0].uris.empty());
  EXPECT_THAT(found[0].note, HasSubstr("LIBUSB_ERROR_ACCESS (permission denied: install the "
                                       "udev rules"));
}

TEST(Discovery, NoUsbAtAllStillListsHid) {
  FakeUsb usb;
  usb.init_result = detail::kUsbErrorOther;
  usb.devices.push_back({FakeUsb::desc(), "PALP-0042", ""});
  FakeHid hid;
  hid.devices.push_back(FakeHid::info("PALP-0042"));
  const auto found = detail::list_devices_with(DiscoveryOptions{}, &usb, &hid);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_THAT(found[0].uris, ElementsAre("hid://PALP-0042"));
  EXPECT_THAT(usb.calls, ElementsAre("init"));
  FakeHid none;
  EXPECT_TRUE(detail::list_devices_with(DiscoveryOptions{}, &usb, &none).empty());
}

TEST(Discovery, OptionsReadTheEnvironment) {
  EXPECT_EQ(DiscoveryOptions{}.vid, 0x1209);
  EXPECT_EQ(DiscoveryOptions{}.pid, 0x0001);
  ::setenv("PALP_USB_VID", "0x1234", 1);
  ::setenv("PALP_USB_PID", "abCD", 1);
  const DiscoveryOptions o;
  EXPECT_EQ(o.vid, 0x1234);
  EXPECT_EQ(o.pid, 0xABCD);
  ::setenv("PALP_USB_PID", "12345", 1);
  try {
    DiscoveryOptions bad;
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "PALP_USB_PID='12345' is not a USB ID (up to 4 hex digits, e.g. 1209 or 0x1209)");
  }
  ::unsetenv("PALP_USB_VID");
  ::unsetenv("PALP_USB_PID");
}

}  // namespace
}  // namespace palp
