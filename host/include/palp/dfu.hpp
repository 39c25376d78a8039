// SPDX-License-Identifier: Apache-2.0
// The DfuSe client: updates a device in ST's ROM DFU bootloader (0483:df11) over libusb, through
// the SDK's UsbApi seam (host/src/transport/usb_api.hpp). usb-dfu-facts.md §5 is the protocol;
// host/src/dfu/README.md lists what the client does, request by request.
//
// One DfuseDevice is one opened device with interface 0, alt setting 0 (the internal flash)
// claimed. Its calls are blocking and bounded in time: every control transfer has a timeout,
// every wait on a busy device a limit. Nothing is erased or written outside what a call names:
// erase_pages() erases only the pages its range touches (never a mass erase; mass_erase() is a
// separate call), and every address is checked against the device's memory-layout string
// (facts §5.8) before any request is sent.
//
// Every failure throws DfuseError. Its message is what the user sees: what was being done, at
// which address, what the device reported (DFU state and status by name, e.g. "dfuERROR,
// errWRITE"), and what to do. The accessors carry the same facts for a program.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "palp/error.hpp"

namespace palp::detail {
class UsbApi;
}

namespace palp::dfu {

/// Where a long call is, reported after each step (erase: each page; download/verify: each
/// wTransferSize block; manifest: once, done = total = 1, when leave() has sent its request).
/// done/total are bytes otherwise (erase: bytes of the pages erased).
struct Progress {
  enum class Phase { erase, download, verify, manifest } phase;
  std::size_t done, total;
};
using ProgressFn = std::function<void(const Progress&)>;

/// "erase", "download", "verify", "manifest".
const char* phase_name(Progress::Phase phase);

/// DFU states and status codes (facts §5.3), with their names as DFU 1.1 spells them.
enum class State : std::uint8_t {
  app_idle = 0, app_detach = 1, dfu_idle = 2, dnload_sync = 3, dnbusy = 4, dnload_idle = 5,
  manifest_sync = 6, manifest = 7, manifest_wait_reset = 8, upload_idle = 9, error = 10,
};
enum class Status : std::uint8_t {
  ok = 0x00, err_target, err_file, err_write, err_erase, err_check_erased, err_prog, err_verify,
  err_address, err_notdone, err_firmware, err_vendor, err_usbr, err_por, err_unknown,
  err_stalledpkt,
};
/// "dfuIDLE", "dfuDNLOAD-SYNC", ... ; "state 42" for a value DFU does not define.
std::string state_name(std::uint8_t state);
/// "OK", "errWRITE", ... ; "status 0x42" for a value DFU does not define.
std::string status_name(std::uint8_t status);

class DfuseError : public palp::Error {
 public:
  enum class Kind {
    not_found,       ///< no device in DFU mode (or not the named serial) within the wait
    access,          ///< the device could not be opened or claimed (permissions, busy)
    bad_layout,      ///< the memory-layout string cannot be parsed
    refused_address, ///< the range is outside the layout or not erasable/writable; nothing sent
    device_status,   ///< the device reported an error status (status()/state() say which)
    stalled,         ///< a request was stalled (LIBUSB_ERROR_PIPE) and recovery did not help
    unplugged,       ///< the device went away (LIBUSB_ERROR_NO_DEVICE)
    timeout,         ///< a transfer timed out, or the device stayed busy past the limit
    protocol,        ///< the device answered something DfuSe does not allow (short status, state)
    usb,             ///< any other libusb failure (usb_error() says which)
    verify_mismatch, ///< read-back differs from what was written (address() = first difference)
  };
  DfuseError(Kind kind, const std::string& message, std::optional<std::uint32_t> address = {},
             std::optional<std::uint8_t> state = {}, std::optional<std::uint8_t> status = {},
             int usb_error = 0)
      : Error(message), kind_(kind), address_(address), state_(state), status_(status),
        usb_error_(usb_error) {}
  Kind kind() const { return kind_; }
  /// The flash address the failure concerns, when there is one.
  std::optional<std::uint32_t> address() const { return address_; }
  /// The device's last reported bState / bStatus (GETSTATUS), when one was read.
  std::optional<std::uint8_t> state() const { return state_; }
  std::optional<std::uint8_t> status() const { return status_; }
  /// The libusb error code (UsbError, negative) behind it; 0 when none.
  int usb_error() const { return usb_error_; }

 private:
  Kind kind_;
  std::optional<std::uint32_t> address_;
  std::optional<std::uint8_t> state_, status_;
  int usb_error_;
};

/// Which device to open: the ROM bootloader's ids (facts §5.7); serial empty = the first found.
struct DfuseTarget {
  std::string serial;
  std::uint16_t vid = 0x0483, pid = 0xDF11;
};

/// One run of equal sectors in the memory-layout string (facts §5.8).
struct MemorySegment {
  std::uint32_t start = 0;      ///< address of its first page
  std::uint32_t page_size = 0;  ///< bytes; also the erase unit
  std::uint32_t pages = 0;
  bool readable = false, erasable = false, writable = false;
  std::uint64_t end() const { return std::uint64_t{start} + std::uint64_t{page_size} * pages; }
};

/// A parsed memory-layout string: "@Internal Flash  /0x08000000/256*02Kg".
struct MemoryLayout {
  std::string name;  ///< text between '@' and the first '/', trailing spaces removed
  std::vector<MemorySegment> segments;

  /// The segment holding address, or null.
  const MemorySegment* find(std::uint32_t address) const;
  /// The pages [address, address + size) touches, as (page start, page size), in order.
  /// Throws DfuseError(refused_address) when any byte is outside the layout or, with
  /// need_erasable / need_writable, in a segment without that attribute.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pages(std::uint32_t address,
                                                             std::size_t size,
                                                             bool need_erasable,
                                                             bool need_writable) const;
};
/// Parses a DfuSe memory-layout string; throws DfuseError(bad_layout) saying what is wrong.
MemoryLayout parse_memory_layout(std::string_view text);

/// Tuning and test hooks; the defaults are for a real device.
struct DfuseOptions {
  /// Timeout of every control transfer.
  std::chrono::milliseconds control_timeout{5000};
  /// Longest the client waits while the device reports dfuDNBUSY for one command or block
  /// (sum of the bwPollTimeouts it asked for, at least 1 ms per poll).
  std::chrono::milliseconds busy_limit{30000};
  /// How often open() looks for the device while waiting for it.
  std::chrono::milliseconds open_poll{100};
  /// How the client waits (bwPollTimeout, open polling); tests pass a fake clock.
  std::function<void(std::chrono::milliseconds)> sleep;  ///< empty = std::this_thread::sleep_for
};

class DfuseDevice {
 public:
  /// Opens the first device (or the one whose serial number is target.serial) with target's
  /// vid:pid, waiting up to `wait` for it to appear (a device re-enumerating after
  /// EnterBootloader takes a moment), claims interface 0 and selects alt setting 0, reads the
  /// memory-layout string and wTransferSize, and brings the device to dfuIDLE (CLRSTATUS from
  /// dfuERROR, ABORT from any other DFU state). Throws DfuseError.
  static DfuseDevice open(std::shared_ptr<detail::UsbApi> usb, const DfuseTarget& target,
                          std::chrono::milliseconds wait, DfuseOptions options = {});

  DfuseDevice(DfuseDevice&&) noexcept;
  DfuseDevice& operator=(DfuseDevice&&) noexcept;
  ~DfuseDevice();  ///< releases the interface and closes the handle (no request sent)

  /// The alt setting's DfuSe string, as the device gives it.
  std::string memory_layout() const;
  /// The same, parsed.
  const MemoryLayout& layout() const;
  /// The serial-number string of the opened device ("" when it has none).
  std::string serial() const;
  /// Bytes per DNLOAD/UPLOAD block: wTransferSize of the DFU functional descriptor, or 2048
  /// (the ROM's, facts §5.1) when the device has none.
  std::size_t transfer_size() const;

  /// Erases every page [address, address + size) touches, one ERASE (0x41 + address) per page;
  /// refuses (before any request) a range outside the layout or not erasable.
  void erase_pages(std::uint32_t address, std::size_t size, const ProgressFn& progress);
  /// Erases the whole flash (DfuSe mass erase, 0x41 alone). Only when a user asked for it.
  void mass_erase(const ProgressFn& progress);
  /// Writes bytes at address in transfer_size() blocks (SET_ADDRESS_POINTER per block, then
  /// DNLOAD block 2); the pages must have been erased. Refuses a range outside the layout or
  /// not writable before any request.
  void download(std::uint32_t address, std::span<const std::uint8_t> bytes,
                const ProgressFn& progress);
  /// Reads size bytes from address (read-back; progress phase verify).
  std::vector<std::uint8_t> upload(std::uint32_t address, std::size_t size,
                                   const ProgressFn& progress);
  /// Starts the application: SET_ADDRESS_POINTER(address), DNLOAD of length 0, GETSTATUS
  /// (manifest). The device then resets or disconnects: an unplug or an error on that last
  /// GETSTATUS is expected and not an error. The DfuseDevice is closed afterwards.
  void leave(std::uint32_t address, const ProgressFn& progress = {});

 private:
  struct Impl;
  explicit DfuseDevice(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace palp::dfu
