// SPDX-License-Identifier: Apache-2.0
// DfuseDevice (palp/dfu.hpp): finding and opening the ROM bootloader, and the erase / download /
// upload / leave sequences of usb-dfu-facts.md §5.5-§5.6 over the requests of dfu_session.hpp.
#include <algorithm>
#include <cstdio>

#include "dfu/dfu_messages.hpp"
#include "dfu/dfu_session.hpp"
#include "palp/dfu.hpp"
#include "transport/usb_api.hpp"

namespace palp::dfu {

using internal::Doing;
using internal::hex32;

namespace {

constexpr int kDfuInterface = 0;             // the ROM's flash is interface 0, alt 0 (facts §5.7)
constexpr std::size_t kRomTransferSize = 2048;  // the ROM's wTransferSize (facts §5.1)
constexpr std::uint8_t kDfuFunctional = 0x21;   // descriptor type (facts §5.1)
constexpr std::size_t kProgramUnit = 8;  // the G474 programs double words (stm32g474 facts §6)

// The fallback command names the image's address (stm32g474 facts §6, "Flash command").
std::string flash_again(std::uint32_t address) {
  return "flash the image again (palpctl flash IMAGE, or dfu-util -d 0483:df11 -a 0 -s " +
         hex32(address) + ":leave -D IMAGE.bin)";
}
std::string erase_advice(std::uint32_t address) {
  return "The image's pages may be partly erased, so the application may not start: " +
         flash_again(address);
}
std::string download_advice(std::uint32_t address) {
  return "The image in flash is incomplete and will not start: " + flash_again(address);
}
constexpr const char* kVerifyAdvice =
    "Nothing was changed by reading: read it back again; if this repeats, flash the image again";
constexpr const char* kLeaveAdvice =
    "The image is in flash: reset or re-plug the board to start it";

std::string describe(const DfuseTarget& t) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04x:%04x", t.vid, t.pid);
  return buf;
}

std::size_t transfer_size_of(const std::vector<detail::UsbAltSetting>& alts) {
  // The DFU functional descriptor follows the interface's last alt setting on the ROM; look in
  // every alt setting's extra bytes, as dfu-util does.
  for (const detail::UsbAltSetting& a : alts) {
    if (a.interface_number != kDfuInterface) continue;
    for (std::size_t k = 0; k + 1 < a.extra.size() && a.extra[k] >= 2; k += a.extra[k]) {
      const std::size_t len = a.extra[k];
      if (a.extra[k + 1] == kDfuFunctional && len >= 7 && k + len <= a.extra.size()) {
        const std::size_t size = a.extra[k + 5] | (a.extra[k + 6] << 8);
        if (size > 0) return size;
      }
    }
  }
  return kRomTransferSize;
}

}  // namespace

struct DfuseDevice::Impl {
  std::shared_ptr<detail::UsbApi> usb;
  detail::UsbHandle handle{};
  bool open = false;
  std::string serial, layout_text;
  MemoryLayout layout;
  std::size_t transfer_size = kRomTransferSize;
  std::optional<internal::Session> session;

  ~Impl() { close(); }
  void close() {
    if (!open) return;
    usb->release_interface(handle, kDfuInterface);
    usb->close(handle);
    usb->exit();
    open = false;
  }
  internal::Session& s() {
    if (!open)
      throw DfuseError(DfuseError::Kind::protocol,
                       "the DFU device was closed (it left DFU mode): open it again");
    return *session;
  }
  void end_in_idle(const Doing& doing) { s().abort(doing); }
};

DfuseDevice::DfuseDevice(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DfuseDevice::DfuseDevice(DfuseDevice&&) noexcept = default;
DfuseDevice& DfuseDevice::operator=(DfuseDevice&&) noexcept = default;
DfuseDevice::~DfuseDevice() = default;

std::string DfuseDevice::memory_layout() const { return impl_->layout_text; }
const MemoryLayout& DfuseDevice::layout() const { return impl_->layout; }
std::string DfuseDevice::serial() const { return impl_->serial; }
std::size_t DfuseDevice::transfer_size() const { return impl_->transfer_size; }

DfuseDevice DfuseDevice::open(std::shared_ptr<detail::UsbApi> usb, const DfuseTarget& target,
                              std::chrono::milliseconds wait, DfuseOptions options) {
  using Kind = DfuseError::Kind;
  const std::string id = describe(target);
  if (const int r = usb->init(); r < 0)
    throw DfuseError(Kind::usb, "USB is not available on this machine (libusb_init: " +
                                    detail::usb_error_name(r) + ")", {}, {}, {}, r);
  auto impl = std::make_unique<Impl>();
  impl->usb = usb;
  std::vector<detail::UsbAltSetting> alts;
  std::vector<std::string> seen;
  int open_error = 0;
  for (std::chrono::milliseconds waited{0};; waited += options.open_poll) {
    std::vector<detail::UsbDevice> list;
    if (const int r = usb->get_device_list(list); r < 0) {
      usb->exit();
      throw DfuseError(Kind::usb, "cannot list the USB devices: " + detail::usb_error_name(r), {},
                       {}, {}, r);
    }
    seen.clear();
    for (detail::UsbDevice d : list) {
      detail::UsbDeviceDescriptor desc;
      if (usb->get_device_descriptor(d, desc) < 0 || desc.vid != target.vid ||
          desc.pid != target.pid)
        continue;
      detail::UsbHandle h{};
      if (const int r = usb->open(d, h); r < 0) {
        open_error = r;
        continue;
      }
      std::string serial;
      if (desc.i_serial != 0) usb->get_string_descriptor_ascii(h, desc.i_serial, serial);
      seen.push_back(serial.empty() ? "(no serial)" : serial);
      if (!target.serial.empty() && serial != target.serial) {
        usb->close(h);
        continue;
      }
      if (const int r = usb->get_active_config_interfaces(d, alts); r < 0) {
        open_error = r;  // its configuration cannot be read: named in the not-found message
        usb->close(h);
        continue;
      }
      impl->handle = h;
      impl->serial = serial;
      impl->open = true;
      break;
    }
    usb->free_device_list();
    if (impl->open || waited >= wait) break;
    internal::sleep_for(options, options.open_poll);
  }
  if (!impl->open) {
    usb->exit();
    if (open_error == detail::kUsbErrorAccess && seen.empty())
      throw DfuseError(Kind::access,
                       "cannot open the DFU device " + id + " (LIBUSB_ERROR_ACCESS): " +
                           detail::kPermissionHint,
                       {}, {}, {}, open_error);
    std::string found;
    for (const std::string& s : seen) found += (found.empty() ? "" : ", ") + s;
    const std::string named = target.serial.empty() ? "" : ", serial " + target.serial;
    const std::string unopened =
        open_error != 0 ? "; one could not be opened or read: " + detail::usb_error_name(open_error)
                        : "";
    throw DfuseError(
        Kind::not_found,
        "no device in DFU mode (" + id + named + ") found within " +
            std::to_string(wait.count()) + " ms" +
            (seen.empty() ? "" : " (found: " + found + ")") + unopened +
            "; put the controller into its bootloader (palpctl flash does it by EnterBootloader; "
            "by hand: hold BOOT0 high while resetting the board) and check the cable",
        {}, {}, {}, open_error);
  }

  const auto fail_open = [&](Kind kind, const std::string& message, int r) {
    impl->close();
    throw DfuseError(kind, message, {}, {}, {}, r);
  };
  const auto alt0 = std::find_if(alts.begin(), alts.end(), [](const detail::UsbAltSetting& a) {
    return a.interface_number == kDfuInterface && a.alt_setting == 0;
  });
  if (alt0 == alts.end() || alt0->interface_class != 0xFE || alt0->interface_subclass != 0x01)
    fail_open(Kind::protocol,
              "the device " + id + " has no DFU interface 0 alt setting 0 (class 0xFE, subclass "
              "0x01): is it an STM32 ROM bootloader? dfu-util -l lists what it has", 0);
  if (usb->kernel_driver_active(impl->handle, kDfuInterface) == 1)
    usb->detach_kernel_driver(impl->handle, kDfuInterface);
  if (const int r = usb->claim_interface(impl->handle, kDfuInterface); r < 0) {
    impl->open = false;  // nothing claimed to release
    usb->close(impl->handle);
    usb->exit();
    std::string why;
    if (r == detail::kUsbErrorBusy) why = " (another program, e.g. dfu-util, has it open)";
    if (r == detail::kUsbErrorAccess) why = std::string("; ") + detail::kPermissionHint;
    throw DfuseError(r == detail::kUsbErrorAccess ? Kind::access : Kind::usb,
                     "cannot claim the DFU interface of " + id + ": " +
                         detail::usb_error_name(r) + why,
                     {}, {}, {}, r);
  }
  if (const int r = usb->set_interface_alt_setting(impl->handle, kDfuInterface, 0); r < 0)
    fail_open(r == detail::kUsbErrorNoDevice ? Kind::unplugged : Kind::usb,
              "cannot select alt setting 0 of the DFU interface of " + id + ": " +
                  detail::usb_error_name(r),
              r);
  if (alt0->i_interface == 0)
    fail_open(Kind::bad_layout, "the device " + id + " names no memory layout (iInterface 0)", 0);
  if (const int r = usb->get_string_descriptor_ascii(impl->handle, alt0->i_interface,
                                                     impl->layout_text);
      r < 0)
    fail_open(r == detail::kUsbErrorNoDevice ? Kind::unplugged : Kind::usb,
              "cannot read the memory-layout string of " + id + ": " + detail::usb_error_name(r),
              r);
  try {
    impl->layout = parse_memory_layout(impl->layout_text);
  } catch (...) {
    impl->close();
    throw;
  }
  impl->transfer_size = transfer_size_of(alts);
  impl->session.emplace(usb, impl->handle, kDfuInterface, std::move(options));
  try {
    impl->session->to_idle(
        {"bringing the DFU device " + id + " to dfuIDLE", {}, "Then try again"});
  } catch (...) {
    impl->close();
    throw;
  }
  return DfuseDevice(std::move(impl));
}

void DfuseDevice::erase_pages(std::uint32_t address, std::size_t size, const ProgressFn& progress) {
  const auto pages = impl_->layout.pages(address, size, true, false);
  internal::Session& s = impl_->s();
  const std::string advice = erase_advice(address);
  std::size_t total = 0, done = 0;
  for (const auto& p : pages) total += p.second;
  for (const auto& [page, page_size] : pages) {
    const std::uint8_t cmd[5] = {0x41, static_cast<std::uint8_t>(page),
                                 static_cast<std::uint8_t>(page >> 8),
                                 static_cast<std::uint8_t>(page >> 16),
                                 static_cast<std::uint8_t>(page >> 24)};
    s.command(cmd, {"erasing the page at " + hex32(page), page, advice});
    done += page_size;
    if (progress) progress({Progress::Phase::erase, done, total});
  }
  if (!pages.empty()) impl_->end_in_idle({"ending the erase", address, advice});
}

void DfuseDevice::mass_erase(const ProgressFn& progress) {
  internal::Session& s = impl_->s();
  std::size_t total = 0;
  for (const MemorySegment& seg : impl_->layout.segments)
    if (seg.erasable) total += std::size_t{seg.page_size} * seg.pages;
  const std::uint8_t cmd[1] = {0x41};
  const std::uint32_t first = impl_->layout.segments.front().start;
  s.command(cmd, {"mass-erasing the flash", {}, erase_advice(first)});
  if (progress) progress({Progress::Phase::erase, total, total});
  impl_->end_in_idle({"ending the mass erase", {}, erase_advice(first)});
}

void DfuseDevice::download(std::uint32_t address, std::span<const std::uint8_t> bytes,
                           const ProgressFn& progress) {
  const std::size_t padded = (bytes.size() + kProgramUnit - 1) / kProgramUnit * kProgramUnit;
  (void)impl_->layout.pages(address, padded, false, true);
  if (address % kProgramUnit != 0)
    throw DfuseError(DfuseError::Kind::refused_address,
                     "downloading to " + hex32(address) + " refused before anything was sent: "
                     "the STM32G474 programs 8-byte double words, the address must be a "
                     "multiple of 8",
                     address);
  internal::Session& s = impl_->s();
  const std::size_t block = impl_->transfer_size;
  const std::string advice = download_advice(address);
  std::vector<std::uint8_t> chunk;
  for (std::size_t off = 0; off < bytes.size(); off += block) {
    const std::size_t n = std::min(block, bytes.size() - off);
    const std::uint32_t at = address + static_cast<std::uint32_t>(off);
    chunk.assign(bytes.begin() + static_cast<std::ptrdiff_t>(off),
                 bytes.begin() + static_cast<std::ptrdiff_t>(off + n));
    chunk.resize((n + kProgramUnit - 1) / kProgramUnit * kProgramUnit, 0xFF);  // erased value
    const std::string what = "writing " + std::to_string(n) + " bytes at " + hex32(at);
    s.set_address(at, {what + " (setting the address pointer)", at, advice});
    s.download_block(2, chunk, {what, at, advice});
    if (progress) progress({Progress::Phase::download, off + n, bytes.size()});
  }
  if (!bytes.empty()) impl_->end_in_idle({"ending the download", address, advice});
}

std::vector<std::uint8_t> DfuseDevice::upload(std::uint32_t address, std::size_t size,
                                              const ProgressFn& progress) {
  for (const auto& [page, page_size] : impl_->layout.pages(address, size, false, false)) {
    (void)page_size;
    if (!impl_->layout.find(page)->readable)
      throw DfuseError(DfuseError::Kind::refused_address,
                       "reading " + hex32(address) + " refused before anything was sent: " +
                           hex32(std::max(page, address)) + " is in a segment that cannot be read",
                       std::max(page, address));
  }
  internal::Session& s = impl_->s();
  std::vector<std::uint8_t> out(size);
  const std::size_t block = impl_->transfer_size;
  std::size_t off = 0;
  while (off < size) {
    // one address pointer per run of blocks: block numbers 2..0xFFFF (facts §5.6)
    const std::uint32_t base = address + static_cast<std::uint32_t>(off);
    s.set_address(base, {"reading at " + hex32(base) + " (setting the address pointer)", base,
                         kVerifyAdvice});
    s.abort({"reading at " + hex32(base) + " (ABORT to dfuIDLE)", base, kVerifyAdvice});
    for (std::uint32_t num = 2; num <= 0xFFFF && off < size; ++num) {
      const std::size_t n = std::min(block, size - off);
      const std::uint32_t at = address + static_cast<std::uint32_t>(off);
      const Doing doing{"reading " + std::to_string(n) + " bytes at " + hex32(at), at,
                        kVerifyAdvice};
      const std::size_t got =
          s.upload_block(static_cast<std::uint16_t>(num), out.data() + off, n, doing);
      if (got != n)
        throw DfuseError(DfuseError::Kind::protocol,
                         doing.what + " failed: the device sent " + std::to_string(got) +
                             " bytes. " + kVerifyAdvice,
                         at);
      off += n;
      if (progress) progress({Progress::Phase::verify, off, size});
    }
  }
  if (size > 0) impl_->end_in_idle({"ending the read-back", address, kVerifyAdvice});
  return out;
}

void DfuseDevice::leave(std::uint32_t address, const ProgressFn& progress) {
  if (impl_->layout.find(address) == nullptr)
    throw DfuseError(DfuseError::Kind::refused_address,
                     "starting the application at " + hex32(address) +
                         " refused before anything was sent: the address is outside the "
                         "device's memory layout \"" + impl_->layout.name + "\"",
                     address);
  internal::Session& s = impl_->s();
  const std::string what = "starting the application at " + hex32(address);
  s.set_address(address, {what + " (setting the address pointer)", address, kLeaveAdvice});
  // DNLOAD of length 0 = leave DFU (facts §5.6); the GETSTATUS after it starts the manifest.
  if (const int r = s.control(false, internal::kDnload, 2, nullptr, 0); r < 0)
    s.fail_transfer(r, {what, address, kLeaveAdvice});
  std::uint8_t b[6] = {};
  const int r = s.control(true, internal::kGetStatus, 0, b, sizeof b);
  // The device resets as it answers, or before: a lost or failed GETSTATUS is expected
  // (facts stm32g474 §6, ":leave quirk"). A reported error is not.
  if (r == 6 && (b[0] != static_cast<std::uint8_t>(Status::ok) ||
                 b[4] == static_cast<std::uint8_t>(State::error))) {
    internal::StatusReply st{b[0], 0, b[4]};
    s.fail_status(st, {what, address, "Reset or re-plug the board; if the application does "
                                      "not start, flash the image again"});
  }
  if (progress) progress({Progress::Phase::manifest, 1, 1});
  impl_->close();
}

}  // namespace palp::dfu
