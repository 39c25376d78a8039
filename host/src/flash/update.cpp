// SPDX-License-Identifier: Apache-2.0
// palp::flash::update (palp/flash.hpp): the steps of a firmware update, each said before it is
// done; with dry_run said and not done.
#include <thread>

#include "flash/calibration_file.hpp"
#include "palp/error.hpp"
#include "palp/flash.hpp"
#include "palp/protocol/handshake.hpp"
#include "palp/protocol/verdict_text.hpp"
#include "probe/exchange.hpp"
#include "probe/probe_impl.hpp"
#include "transport/usb_api.hpp"

namespace palp::flash {

namespace {

using std::chrono::milliseconds;

std::string hex(std::uint32_t v) { return proto::hash_text(v); }
std::string secs(milliseconds t) {
  const long long ms = t.count();
  return ms % 1000 == 0 ? std::to_string(ms / 1000) + " s" : std::to_string(ms) + " ms";
}

class Run {
 public:
  Run(const FirmwareImage& image, const FlashOptions& o, const FlashHooks& h)
      : image_(image), o_(o), h_(h), keep_(proto::board_calibration_flash(
                                          static_cast<proto::BoardId>(image.metadata.board))) {}

  FlashReport go() {
    say("image " + image_.path + " (" + image_.container + "): board " + image_.board() +
        ", firmware " + image_.firmware_version() + ", protocol " + image_.protocol_version() +
        ", " + std::to_string(image_.bytes.size()) + " bytes for " + hex(image_.address) +
        ", size and CRC-32 " + hex(image_.metadata.image_crc32) + " check out");
    std::unique_ptr<Transport> link;
    if (!o_.device_in_dfu) link = identify();
    report_.from_dfu = !link;
    if (link && !bootloader(std::move(link))) return report_;
    if (o_.dry_run) {
      plan_dfu_and_confirm();
      say(std::string("dry run: nothing was sent to the device") +
          (report_.from_dfu ? "" : " but GetDeviceInfo"));
      return report_;
    }
    dfu_stage();
    if (!report_.interrupted) confirm();
    return report_;
  }

 private:
  void say(const std::string& line) {
    report_.steps.push_back(line);
    if (h_.say) h_.say(line);
  }
  bool interrupted() const { return h_.interrupted && h_.interrupted(); }
  void sleep(milliseconds t) const {
    if (h_.sleep) h_.sleep(t);
    else std::this_thread::sleep_for(t);
  }
  std::unique_ptr<Transport> open(milliseconds timeout) const {
    return h_.open ? h_.open(o_.uri, timeout) : open_transport(o_.uri, timeout);
  }
  std::shared_ptr<palp::detail::UsbApi> usb() {
    if (!usb_) usb_ = h_.usb ? h_.usb : palp::detail::make_libusb_api();
    return usb_;
  }
  std::string keep_text() const {
    return keep_.begin == keep_.end ? std::string()
                                    : "; the calibration's pages " + hex(keep_.begin) + ".." +
                                          hex(keep_.end) + " are kept";
  }

  // step 2: GetDeviceInfo (frozen: no session, any protocol); null when auto-detect found DFU
  std::unique_ptr<Transport> identify() {
    std::unique_ptr<Transport> t;
    try {
      t = open(o_.reply_timeout);
    } catch (const ConnectionError& e) {
      if (!o_.auto_detect_dfu || !dfu_present()) throw;
      say(std::string("no palp controller answered at ") + o_.uri + " (" + e.what() +
          "), but a device waits in its ROM DFU bootloader (USB 0483:df11): flashing that "
          "(auto-detected; --device-in-dfu says so)");
      return nullptr;
    }
    const auto r = palp::detail::exchange<proto::DeviceInfo>(
        *t, proto::GetDeviceInfo{}, 1, o_.reply_timeout, "the DeviceInfo reply to GetDeviceInfo",
        "(is it a palp controller, and is its firmware running?)");
    const auto* d = std::get_if<proto::DeviceInfo>(&r);
    if (!d) throw ProtocolError("the device refused GetDeviceInfo, a frozen request (SPEC.md §6.1)");
    device_ = *d;
    const DeviceInfo info = palp::detail::device_info_from(*d);
    report_.before = info;
    say("device " + info.serial + " at " + o_.uri + ": board " + info.board + ", firmware " +
        info.firmware_version + " (git " + info.git_hash + "), protocol " +
        proto::version_text(d->protocol_major, d->protocol_minor));
    const std::string wrong = board_mismatch(image_, info);
    if (!wrong.empty()) throw ConfigError(wrong);
    return t;
  }

  bool dfu_present() {
    try {
      dfu::DfuseDevice::open(usb(), {o_.dfu_serial}, milliseconds(0), dfu_options());
      return true;
    } catch (const Error&) {
      return false;
    }
  }
  dfu::DfuseOptions dfu_options() const {
    dfu::DfuseOptions d;
    d.sleep = h_.sleep;
    return d;
  }

  // steps 3 and 4; false when the update ends here (dry run, interrupted)
  bool bootloader(std::unique_ptr<Transport> link) {
    const proto::ProtocolVersion v{device_.protocol_major, device_.protocol_minor, device_.schema_hash};
    const bool talks = proto::judge(proto::kThisProtocol, v).compatibility !=
                       proto::Compatibility::incompatible;
    const std::string file = o_.calibration_file.empty()
                                 ? detail::default_calibration_path(image_.path, report_.before->serial)
                                 : o_.calibration_file;
    if (talks) {
      detail::check_calibration_path(file);
      say("calibration: read it (GetCalibration), keep it in memory and in " + file);
    } else {
      say("calibration: cannot be read: the device speaks protocol " +
          proto::version_text(v.major, v.minor) + ", which this SDK cannot talk to" + keep_text());
    }
    say("bootloader: stop any program (0 A), then EnterBootloader");
    if (o_.dry_run) return true;
    if (interrupted()) return stopped("before the bootloader");

    if (talks) {
      ConnectOptions co;
      co.timeout = o_.reply_timeout;
      co.reconnect = false;
      Probe probe(std::move(link), co);
      report_.calibration = probe.calibration();
      detail::write_calibration_file(file, *report_.calibration, *report_.before, image_.path);
      report_.calibration_file = file;
      probe.make_safe();
      if (interrupted()) return stopped("before the bootloader");
      probe.enter_bootloader();
    } else {
      const auto r = palp::detail::exchange<proto::Ack>(
          *link, proto::EnterBootloader{proto::kBootloaderMagic}, 2, o_.reply_timeout,
          "the Ack to EnterBootloader");
      if (const auto* nak = std::get_if<proto::Nak>(&r))
        throw DeviceError("EnterBootloader refused: " +
                              std::string(proto::enum_name(nak->error) ? proto::enum_name(nak->error)
                                                                        : "an unknown error") +
                              ": nothing was changed",
                          "EnterBootloader", static_cast<std::uint16_t>(nak->error),
                          nak->field_index, nak->detail);
    }
    return true;
  }

  bool stopped(const std::string& when) {
    report_.interrupted = true;
    say("interrupted " + when + ": nothing was changed");
    return false;
  }

  [[noreturn]] void fail(const std::string& what, bool erased) const {
    throw FlashError(what + "\n" + recovery_text(image_, o_.mass_erase), erased);
  }

  // step 5
  void dfu_stage() {
    say("dfu: wait up to " + secs(o_.dfu_wait) + " for the ROM DFU device (USB 0483:df11)");
    std::optional<dfu::DfuseDevice> dev;
    try {
      dev.emplace(dfu::DfuseDevice::open(usb(), {o_.dfu_serial}, o_.dfu_wait, dfu_options()));
    } catch (const dfu::DfuseError& e) {
      if (report_.from_dfu) throw;
      throw FlashError(std::string(e.what()) +
                           "\nThe controller acknowledged EnterBootloader; nothing was erased. "
                           "Power-cycle it to start its old firmware, or run palpctl flash "
                           "--device-in-dfu " +
                           image_.path + " while it waits in DFU mode.",
                       false);
    }
    say("dfu: device " + dev->serial() + ", memory " + dev->memory_layout());
    if (interrupted()) {
      dev->leave(image_.address);
      report_.interrupted = true;
      say("interrupted before the erase: nothing was erased; the old firmware was started again");
      return;
    }
    const auto progress = [this](const dfu::Progress& p) {
      if (h_.progress) h_.progress(p);
    };
    const std::size_t n = image_.bytes.size();
    bool erased = false;
    try {
      if (o_.mass_erase) {
        say("erase: MASS ERASE of the whole flash, the calibration's pages too (--mass-erase)");
        erased = true;
        dev->mass_erase(progress);
      } else {
        say(erase_line());
        erased = true;
        dev->erase_pages(image_.address, n, progress);
      }
      say(download_line());
      dev->download(image_.address, image_.bytes, progress);
      say(verify_line());
      const std::vector<std::uint8_t> back = dev->upload(image_.address, n, progress);
      for (std::size_t k = 0; k < n; ++k)
        if (k >= back.size() || back[k] != image_.bytes[k])
          fail("verify: the flash at " + hex(static_cast<std::uint32_t>(image_.address + k)) +
                   " reads back other than the image (byte " + std::to_string(k) + " of " +
                   std::to_string(n) + ")",
               true);
      say(leave_line());
      dev->leave(image_.address);
    } catch (const dfu::DfuseError& e) {
      if (!erased) throw;
      fail(e.what(), true);
    }
  }

  std::string erase_line() const {
    return "erase: the pages under " + hex(image_.address) + ".." +
           hex(static_cast<std::uint32_t>(image_.address + image_.bytes.size())) + " only" +
           keep_text();
  }
  std::string download_line() const {
    return "download: " + std::to_string(image_.bytes.size()) + " bytes to " + hex(image_.address);
  }
  std::string verify_line() const {
    return "verify: read the " + std::to_string(image_.bytes.size()) + " bytes back and compare";
  }
  std::string leave_line() const { return "leave: start the new firmware at " + hex(image_.address); }
  std::string confirm_line() const {
    return "confirm: wait up to " + secs(o_.app_wait) + " for the controller at " + o_.uri +
           ", check board " + image_.board() + " and firmware " + image_.firmware_version() +
           (report_.from_dfu ? ", read its calibration"
                             : ", compare its calibration with the kept one and write that back "
                               "if they differ");
  }

  void plan_dfu_and_confirm() {
    say("dfu: wait up to " + secs(o_.dfu_wait) + " for the ROM DFU device (USB 0483:df11)");
    say(o_.mass_erase ? "erase: MASS ERASE of the whole flash, the calibration's pages too "
                        "(--mass-erase)"
                      : erase_line());
    say(download_line());
    say(verify_line());
    say(leave_line());
    say(confirm_line());
  }

  // step 6
  void confirm() {
    say(confirm_line());
    ConnectOptions co;
    co.timeout = o_.reply_timeout;
    co.reconnect = false;
    const auto until = std::chrono::steady_clock::now() + o_.app_wait;
    std::optional<Probe> probe;
    std::string last;
    while (!probe) {
      try {
        probe.emplace(open(o_.reply_timeout), co);
      } catch (const VersionError& e) {
        fail(std::string("the new firmware is running but this SDK cannot talk to it: ") + e.what(),
             false);
      } catch (const Error& e) {
        last = e.what();
        if (std::chrono::steady_clock::now() >= until)
          fail("the image was written and verified and started, but no controller answered at " +
                   o_.uri + " within " + secs(o_.app_wait) + " (" + last +
                   "). Power-cycle the controller; if it still does not answer, put it into its "
                   "bootloader (BOOT0) and flash again.",
               false);
        sleep(milliseconds(200));
      }
    }
    const DeviceInfo info = probe->info();
    report_.after = info;
    if (info.board != image_.board() || info.firmware_version != image_.firmware_version())
      fail("after the update device " + info.serial + " reports board " + info.board +
               ", firmware " + info.firmware_version + "; the image is board " + image_.board() +
               ", firmware " + image_.firmware_version(),
           false);
    say("device " + info.serial + " runs firmware " + info.firmware_version + " (git " +
        info.git_hash + ")");
    const Calibration now = probe->calibration();
    if (!report_.calibration) {
      report_.calibration = now;
      say("calibration: read (nothing kept to compare it with)");
      return;
    }
    if (detail::calibration_bytes(now) == detail::calibration_bytes(*report_.calibration)) {
      say("calibration: unchanged");
      return;
    }
    say("calibration: differs from the kept one: writing it back (SetCalibration, CommitCalibration)");
    probe->set_calibration(*report_.calibration);
    probe->commit_calibration();
    if (detail::calibration_bytes(probe->calibration()) !=
        detail::calibration_bytes(*report_.calibration))
      fail("the calibration read after writing it back still differs from the kept one (" +
               report_.calibration_file + ")",
           false);
    report_.calibration_restored = true;
    say("calibration: restored");
  }

  const FirmwareImage& image_;
  const FlashOptions& o_;
  const FlashHooks& h_;
  const proto::FlashRange keep_;
  std::shared_ptr<palp::detail::UsbApi> usb_;
  proto::DeviceInfo device_{};
  FlashReport report_;
};

}  // namespace

FlashReport update(const FirmwareImage& image, const FlashOptions& options, const FlashHooks& hooks) {
  return Run(image, options, hooks).go();
}

}  // namespace palp::flash
