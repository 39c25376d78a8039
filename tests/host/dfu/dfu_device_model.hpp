// SPDX-License-Identifier: Apache-2.0
// A model of the STM32G474's ROM DFU bootloader (0483:df11) as the host sees it through the
// SDK's UsbApi seam: written from /work/shared/reference/usb-dfu-facts.md §5 and
// stm32g474-facts.md §1.1/§6, not from the client, so the client's tests check it against the
// documented device and not against itself.
//
// DfuRom is the DFU interface (facts §5.2-§5.6): the state machine dfuIDLE, dfuDNLOAD-SYNC,
// dfuDNBUSY, dfuDNLOAD-IDLE, dfuMANIFEST-SYNC/dfuMANIFEST, dfuUPLOAD-IDLE, dfuERROR; the
// GETSTATUS record with bwPollTimeout; the DfuSe commands (block 0: SET_ADDRESS_POINTER 0x21,
// ERASE 0x41 page / mass, READ_UNPROTECT 0x92); data blocks at (wBlockNum - 2) x wTransferSize +
// Address_Pointer; leave by a zero-length DNLOAD. The flash: 512 KB at 0x08000000, 2 KB pages
// (dual-bank, facts stm32g474 §1.1), erased = 0xFF, programmed in 8-byte double words, only
// where erased. Time is virtual: advance() moves it (the client's sleep hook calls it).
//
// Where the facts leave a choice, the model's answer (marked "model:") is the strict one:
//  - a request the current state does not accept is STALLed and the device enters dfuERROR with
//    errSTALLEDPKT (DFU 1.1; facts §5.5 for DNLOAD and unknown commands);
//  - GETSTATUS asked before the bwPollTimeout it gave elapsed answers dfuDNBUSY again and is
//    counted in early_polls (a client that does not wait is caught);
//  - a write to bytes not erased: dfuERROR + errCHECK_ERASED, nothing written; a write not on a
//    double-word boundary or length: dfuERROR + errADDRESS; an address outside the flash:
//    dfuERROR + errTARGET (AN2662, facts §5.5);
//  - leave is accepted in dfuDNLOAD-IDLE (after SET_ADDRESS_POINTER, as dfu-util does it).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "transport/usb_api.hpp"

namespace palp::dfumodel {

enum class DfuState : std::uint8_t {  // facts §5.3
  appIDLE = 0, appDETACH, dfuIDLE, dfuDNLOAD_SYNC, dfuDNBUSY, dfuDNLOAD_IDLE, dfuMANIFEST_SYNC,
  dfuMANIFEST, dfuMANIFEST_WAIT_RESET, dfuUPLOAD_IDLE, dfuERROR,
};
enum class DfuStatus : std::uint8_t {  // facts §5.3
  OK = 0, errTARGET, errFILE, errWRITE, errERASE, errCHECK_ERASED, errPROG, errVERIFY, errADDRESS,
  errNOTDONE, errFIRMWARE, errVENDOR, errUSBR, errPOR, errUNKNOWN, errSTALLEDPKT,
};

/// Faults a test injects.
struct DfuFaults {
  std::optional<std::uint32_t> write_error_page;   ///< programming into this page: errWRITE
  std::optional<std::uint32_t> verify_error_page;  ///< programming into it: a bit flips, errVERIFY
  std::optional<std::uint8_t> stall_request;  ///< the next request with this bRequest is STALLed
  /// false: the STALL puts the device in dfuERROR/errSTALLEDPKT (DFU 1.1's rule); true: the state
  /// stays (a ROM that stalls GETSTATUS while it programs, facts §5.5)
  bool stall_keeps_state = false;
  /// a request with this bRequest, after lose_skip of them went through, is lost: no effect,
  /// the host's transfer times out
  std::optional<std::uint8_t> lose_request;
  int lose_skip = 0;
  int unplug_after = -1;     ///< control transfers served before the device vanishes (-1: never)
  bool stuck_busy = false;   ///< a command or block never finishes (dfuDNBUSY forever)
};

class DfuRom {
 public:
  static constexpr std::uint32_t kFlashBase = 0x08000000;  // stm32g474 facts §1.1
  static constexpr std::uint32_t kFlashSize = 512 * 1024;
  static constexpr std::uint32_t kPageSize = 2048;         // dual-bank mode, 256 pages
  static constexpr std::uint16_t kTransferSize = 2048;     // facts §5.1 (ROM example)

  std::vector<std::uint8_t> flash = std::vector<std::uint8_t>(kFlashSize, 0xFF);
  DfuFaults faults;
  std::uint32_t erase_poll_ms = 25;    ///< bwPollTimeout while a page erase runs
  std::uint32_t program_poll_ms = 5;   ///< while a block is programmed
  std::uint32_t command_poll_ms = 1;   ///< while SET_ADDRESS_POINTER runs
  std::uint32_t mass_erase_poll_ms = 200;

  // What happened, for the tests.
  std::uint64_t now_ms = 0;
  int early_polls = 0;                 ///< GETSTATUS before the bwPollTimeout elapsed
  int illegal_requests = 0;            ///< STALLs the client earned (not injected ones)
  int transfers = 0;                   ///< control transfers seen
  std::vector<std::uint32_t> erased_pages;  ///< page erase commands, in order
  int mass_erases = 0;
  bool unplugged = false;
  bool reset = false;                  ///< left DFU: the application was started
  std::uint32_t started_at = 0;        ///< the address pointer when it left

  DfuState state() const { return state_; }
  DfuStatus status() const { return status_; }
  std::uint32_t address_pointer() const { return pointer_; }
  void advance(std::uint64_t ms) { now_ms += ms; }
  /// Puts the device in a state (a test's starting point: left in dfuERROR by a previous host).
  void force(DfuState s, DfuStatus st) { state_ = s; status_ = st; }
  std::uint8_t* at(std::uint32_t address) { return &flash[address - kFlashBase]; }

  /// One control transfer on the DFU interface; libusb's result.
  int control(std::uint8_t type, std::uint8_t request, std::uint16_t value, std::uint16_t index,
              std::uint8_t* data, std::uint16_t length) {
    if (unplugged || reset) return detail::kUsbErrorNoDevice;
    if (faults.unplug_after >= 0 && transfers >= faults.unplug_after) {
      unplugged = true;
      return detail::kUsbErrorNoDevice;
    }
    ++transfers;
    if (faults.stall_request && *faults.stall_request == request) {
      faults.stall_request.reset();
      if (faults.stall_keeps_state) return detail::kUsbErrorPipe;
      return stall(false);
    }
    if (faults.lose_request && *faults.lose_request == request && faults.lose_skip-- == 0) {
      faults.lose_request.reset();
      return detail::kUsbErrorTimeout;
    }
    const bool in = (type & 0x80) != 0;
    if ((type & 0x7F) != 0x21 || index != 0) return stall();
    switch (request) {
      case 1: return in ? stall() : dnload(value, data, length);
      case 2: return in ? upload(value, data, length) : stall();
      case 3: return in ? get_status(data, length) : stall();
      case 4: return in ? stall() : clear_status();
      case 5:
        if (!in || length < 1) return stall();
        data[0] = static_cast<std::uint8_t>(state_);
        return 1;
      case 6: return in ? stall() : abort();
      default: return stall();  // DETACH and unknown requests: the ROM is already in DFU mode
    }
  }

 private:
  enum class Op { none, set_pointer, erase_page, mass_erase, unprotect, write };

  int stall(bool illegal = true) {
    if (illegal) ++illegal_requests;
    if (state_ != DfuState::dfuERROR) status_ = DfuStatus::errSTALLEDPKT;
    state_ = DfuState::dfuERROR;
    return detail::kUsbErrorPipe;
  }

  int dnload(std::uint16_t block, const std::uint8_t* data, std::uint16_t length) {
    if (state_ != DfuState::dfuIDLE && state_ != DfuState::dfuDNLOAD_IDLE) return stall();
    if (length > kTransferSize) return stall();
    if (length == 0) {  // leave DFU (facts §5.6)
      if (state_ != DfuState::dfuDNLOAD_IDLE) return stall();  // model: after SET_ADDRESS only
      state_ = DfuState::dfuMANIFEST_SYNC;
      return 0;
    }
    op_data_.assign(data, data + length);
    if (block == 0) {
      const std::uint8_t cmd = data[0];
      if (cmd == 0x21 && length == 5) op_ = Op::set_pointer;
      else if (cmd == 0x41 && length == 5) op_ = Op::erase_page;
      else if (cmd == 0x41 && length == 1) op_ = Op::mass_erase;
      else if (cmd == 0x92 && length == 1) op_ = Op::unprotect;
      else return stall();  // unknown command: dfuERROR / errSTALLEDPKT (facts §5.5)
    } else if (block == 1) {
      return stall();  // not used (facts §5.5)
    } else {
      op_ = Op::write;
      op_address_ = static_cast<std::uint32_t>((block - 2u) * kTransferSize) + pointer_;
    }
    state_ = DfuState::dfuDNLOAD_SYNC;
    return length;
  }

  static std::uint32_t le32(const std::vector<std::uint8_t>& b) {
    return b[1] | (b[2] << 8) | (b[3] << 16) | (static_cast<std::uint32_t>(b[4]) << 24);
  }
  static bool in_flash(std::uint64_t a, std::uint64_t n) {
    return a >= kFlashBase && a + n <= std::uint64_t{kFlashBase} + kFlashSize;
  }
  std::uint32_t poll_for(Op op) const {
    switch (op) {
      case Op::erase_page: return erase_poll_ms;
      case Op::mass_erase: case Op::unprotect: return mass_erase_poll_ms;
      case Op::write: return program_poll_ms;
      default: return command_poll_ms;
    }
  }

  // Runs the pending operation; the status it ends with.
  DfuStatus execute() {
    switch (op_) {
      case Op::set_pointer: {
        const std::uint32_t a = le32(op_data_);
        if (!in_flash(a, 1)) return DfuStatus::errTARGET;
        pointer_ = a;
        return DfuStatus::OK;
      }
      case Op::erase_page: {
        const std::uint32_t a = le32(op_data_);
        if (!in_flash(a, 1)) return DfuStatus::errTARGET;
        const std::uint32_t page = a - (a - kFlashBase) % kPageSize;
        std::fill_n(at(page), kPageSize, 0xFF);
        erased_pages.push_back(page);
        return DfuStatus::OK;
      }
      case Op::mass_erase:
        std::fill(flash.begin(), flash.end(), 0xFF);
        ++mass_erases;
        return DfuStatus::OK;
      case Op::unprotect:
        std::fill(flash.begin(), flash.end(), 0xFF);
        reset = true;
        return DfuStatus::OK;
      case Op::write: return write();
      case Op::none: break;
    }
    return DfuStatus::errUNKNOWN;
  }

  DfuStatus write() {
    const std::uint32_t a = op_address_;
    const std::size_t n = op_data_.size();
    if (!in_flash(a, n)) return DfuStatus::errTARGET;
    if (a % 8 != 0 || n % 8 != 0) return DfuStatus::errADDRESS;
    const auto touches = [&](std::optional<std::uint32_t> page) {
      return page && a < *page + kPageSize && a + n > *page;
    };
    if (touches(faults.write_error_page)) return DfuStatus::errWRITE;
    if (!std::all_of(at(a), at(a) + n, [](std::uint8_t b) { return b == 0xFF; }))
      return DfuStatus::errCHECK_ERASED;
    std::copy(op_data_.begin(), op_data_.end(), at(a));
    if (touches(faults.verify_error_page)) {
      *at(std::max(a, *faults.verify_error_page)) ^= 0x01;
      return DfuStatus::errVERIFY;
    }
    return DfuStatus::OK;
  }

  int get_status(std::uint8_t* data, std::uint16_t length) {
    if (length < 6) return stall();
    std::uint32_t poll = 0;
    DfuState reply = state_;
    switch (state_) {
      case DfuState::dfuDNLOAD_SYNC:  // the operation starts now (facts §5.5)
        poll = poll_for(op_);
        busy_until_ = now_ms + poll;
        state_ = reply = DfuState::dfuDNBUSY;
        break;
      case DfuState::dfuDNBUSY:
        if (faults.stuck_busy || now_ms < busy_until_) {
          if (!faults.stuck_busy) ++early_polls;
          poll = faults.stuck_busy ? poll_for(op_)
                                   : static_cast<std::uint32_t>(busy_until_ - now_ms);
          break;
        }
        status_ = execute();
        op_ = Op::none;
        state_ = reply = status_ == DfuStatus::OK ? DfuState::dfuDNLOAD_IDLE : DfuState::dfuERROR;
        break;
      case DfuState::dfuMANIFEST_SYNC:  // reports dfuMANIFEST and starts the application
        reply = DfuState::dfuMANIFEST;
        // manifestation-intolerant (bmAttributes 0x0B, facts §5.1): it would wait for a reset in
        // dfuMANIFEST-WAIT-RESET; the ROM resets itself (facts §5.6), so the device is gone
        state_ = DfuState::dfuMANIFEST_WAIT_RESET;
        reset = true;
        started_at = pointer_;
        break;
      default: break;
    }
    data[0] = static_cast<std::uint8_t>(status_);
    data[1] = static_cast<std::uint8_t>(poll);
    data[2] = static_cast<std::uint8_t>(poll >> 8);
    data[3] = static_cast<std::uint8_t>(poll >> 16);
    data[4] = static_cast<std::uint8_t>(reply);
    data[5] = 0;
    return 6;
  }

  int clear_status() {
    if (state_ != DfuState::dfuERROR) return stall();
    state_ = DfuState::dfuIDLE;
    status_ = DfuStatus::OK;
    return 0;
  }

  int abort() {
    if (state_ != DfuState::dfuIDLE && state_ != DfuState::dfuDNLOAD_IDLE &&
        state_ != DfuState::dfuUPLOAD_IDLE)
      return stall();
    state_ = DfuState::dfuIDLE;
    return 0;
  }

  int upload(std::uint16_t block, std::uint8_t* data, std::uint16_t length) {
    if (state_ != DfuState::dfuIDLE && state_ != DfuState::dfuUPLOAD_IDLE) return stall();
    if (length > kTransferSize || block == 1) return stall();
    if (block == 0) {  // Get commands (facts §5.5)
      const std::uint8_t cmds[] = {0x00, 0x21, 0x41, 0x92};
      const std::uint16_t n = std::min<std::uint16_t>(length, sizeof cmds);
      std::copy(cmds, cmds + n, data);
      state_ = n < length ? DfuState::dfuIDLE : DfuState::dfuUPLOAD_IDLE;
      return n;
    }
    const std::uint64_t a = std::uint64_t{block - 2u} * kTransferSize + pointer_;
    const std::uint64_t end = std::uint64_t{kFlashBase} + kFlashSize;
    const std::uint16_t n =
        a >= end ? 0 : static_cast<std::uint16_t>(std::min<std::uint64_t>(length, end - a));
    if (n > 0) std::copy_n(at(static_cast<std::uint32_t>(a)), n, data);
    state_ = n < length ? DfuState::dfuIDLE : DfuState::dfuUPLOAD_IDLE;  // short reply ends it
    return n;
  }

  DfuState state_ = DfuState::dfuIDLE;
  DfuStatus status_ = DfuStatus::OK;
  std::uint32_t pointer_ = kFlashBase;  // AN2662: 0x08000000 when none was set (facts §5.6)
  Op op_ = Op::none;
  std::vector<std::uint8_t> op_data_;
  std::uint32_t op_address_ = 0;
  std::uint64_t busy_until_ = 0;
};

/// The bus with one ROM bootloader on it, as UsbApi: descriptors (facts §5.1, §5.7, stm32g474
/// facts §6), the DFU interface's alt settings and strings, the control transfers to DfuRom.
class DfuBus final : public detail::UsbApi {
 public:
  static constexpr const char* kFlashLayout = "@Internal Flash  /0x08000000/256*02Kg";  // §5.7
  /// model: the option-byte alt's string; facts §6 gives only its start address 0x1FFF7800.
  static constexpr const char* kOptionLayout = "@Option Bytes   /0x1FFF7800/01*048 e";
  static constexpr std::uint8_t kFunctional[9] = {9, 0x21, 0x0B, 0xFF, 0x00,  // facts §5.1
                                                  0x00, 0x08, 0x1A, 0x01};

  DfuRom rom;
  std::string serial = "206C35A35430";
  std::uint64_t appears_at_ms = 0;  ///< the device enumerates at this virtual time
  std::vector<std::string> calls;

  int init() override { calls.push_back("init"); return 0; }
  void exit() override { calls.push_back("exit"); }
  int get_device_list(std::vector<detail::UsbDevice>& list) override {
    list.clear();
    if (!rom.unplugged && !rom.reset && rom.now_ms >= appears_at_ms)
      list.push_back(static_cast<detail::UsbDevice>(1));
    return static_cast<int>(list.size());
  }
  void free_device_list() override {}
  int get_device_descriptor(detail::UsbDevice, detail::UsbDeviceDescriptor& o) override {
    o = {0x0483, 0xDF11, 0x2200, 2, 3};
    return 0;
  }
  int open_error = 0;  ///< what open() returns (LIBUSB_ERROR_ACCESS: no udev rule)
  int open(detail::UsbDevice, detail::UsbHandle& h) override {
    calls.push_back("open");
    if (open_error != 0) return open_error;
    h = static_cast<detail::UsbHandle>(1);
    return 0;
  }
  void close(detail::UsbHandle) override { calls.push_back("close"); }
  int get_string_descriptor_ascii(detail::UsbHandle, std::uint8_t index, std::string& o) override {
    if (rom.unplugged) return detail::kUsbErrorNoDevice;
    switch (index) {
      case 2: o = "DFU in FS Mode"; break;
      case 3: o = serial; break;
      case 4: o = kFlashLayout; break;
      case 5: o = kOptionLayout; break;
      default: return detail::kUsbErrorPipe;
    }
    return static_cast<int>(o.size());
  }
  int kernel_driver_active(detail::UsbHandle, int) override { return 0; }
  int detach_kernel_driver(detail::UsbHandle, int) override { return 0; }
  int claim_interface(detail::UsbHandle, int i) override {
    calls.push_back("claim_interface " + std::to_string(i));
    return 0;
  }
  int release_interface(detail::UsbHandle, int i) override {
    calls.push_back("release_interface " + std::to_string(i));
    return rom.unplugged || rom.reset ? detail::kUsbErrorNoDevice : 0;
  }
  int bulk_transfer(detail::UsbHandle, std::uint8_t, std::uint8_t*, int, int& transferred,
                    unsigned) override {
    transferred = 0;
    return detail::kUsbErrorPipe;  // the DFU interface has no bulk endpoints
  }
  int get_active_config_interfaces(detail::UsbDevice,
                                   std::vector<detail::UsbAltSetting>& out) override {
    detail::UsbAltSetting flash{0, 0, 0xFE, 0x01, 0x02, 4, {}};
    detail::UsbAltSetting options{0, 1, 0xFE, 0x01, 0x02, 5, {}};
    options.extra.assign(std::begin(kFunctional), std::end(kFunctional));  // after the last alt
    out = {flash, options};
    return 0;
  }
  int set_interface_alt_setting(detail::UsbHandle, int i, int alt) override {
    calls.push_back("set_interface_alt_setting " + std::to_string(i) + " " + std::to_string(alt));
    return 0;
  }
  int control_transfer(detail::UsbHandle, std::uint8_t type, std::uint8_t request,
                       std::uint16_t value, std::uint16_t index, std::uint8_t* data,
                       std::uint16_t length, unsigned timeout_ms) override {
    if (timeout_ms == 0) ++zero_timeouts;
    max_timeout_ms = std::max(max_timeout_ms, timeout_ms);
    return rom.control(type, request, value, index, data, length);
  }
  int zero_timeouts = 0;  ///< control transfers handed "no timeout" (must stay 0)
  unsigned max_timeout_ms = 0;  ///< the longest timeout a control transfer was given
};

}  // namespace palp::dfumodel
