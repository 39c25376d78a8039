// SPDX-License-Identifier: Apache-2.0
// Updating a probe controller's firmware (issue 21): what `palpctl flash IMAGE` does, as a call a
// lab's own tooling can make.
//
//   const auto image = palp::flash::read_image("palp-probe-controller.dfu");   // .bin/.elf/.dfu
//   palp::flash::FlashOptions o;  o.uri = "usb://";
//   palp::flash::update(image, o, {.say = [](const std::string& line) { std::cerr << line << '\n'; }});
//
// The steps, in order (FlashOptions::dry_run prints them and does none):
//   1. image: read the file, its metadata block (protocol/.../image_metadata.hpp) checked: size
//      and CRC-32 (a corrupt image), and that it speaks a protocol this SDK can talk to;
//   2. identify: GetDeviceInfo on the controller (a frozen request, SPEC.md §6.1: it works
//      whatever protocol the device speaks, and opens no session), and refuse an image for
//      another board. Nothing has been sent that changes the device up to here;
//   3. calibration: on a device this SDK can talk to, read it (GetCalibration) and keep it, in
//      memory and in a file (FlashOptions::calibration_file: never over a file palp did not write);
//   4. bootloader: make_safe() (no program, 0 A), then EnterBootloader with its magic;
//   5. DFU: open the ROM DFU device (0483:df11, palp/dfu.hpp) once it enumerates; erase the pages
//      the image covers (a mass erase only with FlashOptions::mass_erase), download, read back
//      and compare, leave (start the application);
//   6. confirm: wait for the controller to enumerate again, check its DeviceInfo (board,
//      firmware version) against the image, re-read the calibration and, when it differs from
//      the kept one, write it back (SetCalibration + CommitCalibration) and read it again.
// Every refusal before step 4 is a ConfigError: the device is untouched. interrupted() is polled
// up to the erase: before it, an interruption ends the update with nothing changed (a device
// already in DFU is sent back to its old application). A failure from the erase on is a
// FlashError whose message says what state the device is in and exactly how to recover
// (recovery_text()).
//
// A device already in its ROM bootloader (FlashOptions::device_in_dfu, or found there when no
// controller answers at the URI: auto_detect_dfu) is flashed from step 5; its board cannot be
// asked and its calibration cannot be read (the calibration's flash pages are not erased).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "palp/dfu.hpp"
#include "palp/probe.hpp"
#include "palp/protocol/image_metadata.hpp"

namespace palp::detail {
class UsbApi;
}

namespace palp::flash {

using namespace std::chrono_literals;

/// A firmware image from a file, its metadata checked (read_image).
struct FirmwareImage {
  std::string path;                ///< the file as given
  std::string container;           ///< "bin", "ELF", "DfuSe"
  std::uint32_t address = 0;       ///< where byte 0 goes: the board's image address
  std::vector<std::uint8_t> bytes;  ///< the image (as in the .bin)
  proto::ImageMetadata metadata{};

  std::string board() const;             ///< "stm32g474"
  std::string firmware_version() const;  ///< "0.4.0"
  std::string protocol_version() const;  ///< "1.1"
};

/// Reads path (.bin, .elf or .dfu, told by content) and checks its metadata: a palp image of a
/// known board, whole (size and CRC match), loading where its board's images start, speaking a
/// protocol this SDK is compatible with. Throws ConfigError "IMAGE: why" otherwise.
FirmwareImage read_image(const std::string& path);

/// Why image must not go onto the device info describes ("" = it may): another board.
std::string board_mismatch(const FirmwareImage& image, const DeviceInfo& info);

/// The lines that recover a device whose flash was erased (it waits in its ROM bootloader):
/// `palpctl flash --device-in-dfu IMAGE` and the dfu-util command for this image's file.
/// mass_erased: the calibration's pages were erased too (FlashOptions::mass_erase).
std::string recovery_text(const FirmwareImage& image, bool mass_erased = false);

struct FlashOptions {
  std::string uri = "usb://";  ///< the controller while it runs palp firmware
  bool device_in_dfu = false;  ///< the device already waits in its ROM bootloader: start at step 5
  bool auto_detect_dfu = true;  ///< no controller at uri, but a DFU device: flash that (said so)
  bool mass_erase = false;     ///< erase the whole flash, calibration included (asked for only)
  bool dry_run = false;        ///< say every step, do none (nothing is sent to the device)
  /// Where the kept calibration is written; "" = beside the image: IMAGE.calibration-SERIAL.json.
  std::string calibration_file;
  std::string dfu_serial;      ///< the DFU device's serial ("" = the first found)
  std::chrono::milliseconds reply_timeout = 2000ms;  ///< each protocol reply
  std::chrono::milliseconds dfu_wait = 10000ms;  ///< for the DFU device after EnterBootloader
  std::chrono::milliseconds app_wait = 15000ms;  ///< for the controller after leaving DFU
};

/// What update() needs from its surroundings; tests replace them.
struct FlashHooks {
  /// One line per step, for a person (palpctl: stderr). Empty: silent.
  std::function<void(const std::string&)> say;
  /// Bytes done per DFU phase.
  dfu::ProgressFn progress;
  /// Polled up to the erase; true ends the update with nothing changed.
  std::function<bool()> interrupted;
  /// The libusb seam for the DFU device; null = libusb.
  std::shared_ptr<palp::detail::UsbApi> usb;
  /// Opens the controller's byte stream; null = open_transport(uri).
  std::function<std::unique_ptr<Transport>(const std::string& uri, std::chrono::milliseconds)>
      open;
  /// How the DFU client waits (dfu::DfuseOptions::sleep) and how update() waits between tries
  /// for the re-enumerated controller; empty = sleep_for.
  std::function<void(std::chrono::milliseconds)> sleep;
};

/// What update() did (with dry_run: what it would do).
struct FlashReport {
  std::vector<std::string> steps;            ///< the lines said, in order
  std::optional<DeviceInfo> before, after;   ///< the controller before and after
  std::optional<Calibration> calibration;    ///< the calibration kept (none: not readable)
  std::string calibration_file;              ///< where it was written ("" = nowhere)
  bool calibration_restored = false;         ///< it differed after the update and was written back
  bool from_dfu = false;                     ///< started with the device in DFU
  bool interrupted = false;                  ///< FlashHooks::interrupted ended it before the erase
};

/// Runs the update (steps above). Throws ConfigError before anything changed (a wrong board, a
/// calibration file palp did not write, ...), ConnectionError / TimeoutError / VersionError /
/// DeviceError from the controller before EnterBootloader, FlashError from then on.
FlashReport update(const FirmwareImage& image, const FlashOptions& options,
                   const FlashHooks& hooks = {});

}  // namespace palp::flash
