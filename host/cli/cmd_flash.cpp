// SPDX-License-Identifier: Apache-2.0
// palpctl flash IMAGE: a firmware update through palp::flash::update (palp/flash.hpp), with its
// steps and the DFU progress on stderr, --dry-run's plan on stdout, Ctrl-C honoured up to the
// erase.
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>

#include "common.hpp"
#include "palp/flash.hpp"
#include "palp/result.hpp"

namespace palpctl {

namespace {

struct FlashArgs {
  std::string image;
  bool dry_run = false, device_in_dfu = false, mass_erase = false;
  std::string calibration_file, dfu_serial;
  double dfu_wait_s = 10, reconnect_s = 15;
  bool uri_given = false;  ///< --uri or $PALP_URI; else flash talks to usb://
};

std::chrono::milliseconds ms(double s) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(s * 1e3));
}

int flash(const Context& ctx, const FlashArgs& a) {
  const auto image = palp::flash::read_image(a.image);
  palp::flash::FlashOptions o;
  o.uri = a.uri_given ? ctx.uri : "usb://";
  o.device_in_dfu = a.device_in_dfu;
  o.mass_erase = a.mass_erase;
  o.dry_run = a.dry_run;
  o.calibration_file = a.calibration_file;
  o.dfu_serial = a.dfu_serial;
  o.reply_timeout = ms(ctx.timeout_s);
  o.dfu_wait = ms(a.dfu_wait_s);
  o.app_wait = ms(a.reconnect_s);

  palp::flash::FlashHooks h;
  const bool show = !ctx.json;
  h.say = [&](const std::string& line) {
    if (!show) return;
    (a.dry_run ? std::cout : std::cerr) << "flash: " << line << '\n' << std::flush;
  };
  if (a.mass_erase && show)
    std::cerr << "flash: warning: --mass-erase erases the whole flash, the calibration's pages "
                 "too; the calibration is written back from the kept copy afterwards\n";
  std::optional<Progress> bar;
  std::optional<palp::dfu::Progress::Phase> phase;
  std::uint64_t done = 0;
  h.progress = [&](const palp::dfu::Progress& p) {
    if (phase != p.phase) {
      if (bar) bar->finish(done);
      phase = p.phase;
      bar.emplace(std::string("flash: ") + palp::dfu::phase_name(p.phase), p.total, show, "bytes");
    }
    done = p.done;
    bar->update(p.done);
  };
  if (!a.dry_run) {
    catch_interrupts();
    h.interrupted = [] { return interrupted(); };
  }
  const palp::flash::FlashReport r = palp::flash::update(image, o, h);
  if (bar) bar->finish(done);
  if (ctx.json) {
    json j = {{"image", image.path},
              {"dry_run", a.dry_run},
              {"from_dfu", r.from_dfu},
              {"interrupted", r.interrupted},
              {"steps", r.steps},
              {"calibration_file", r.calibration_file.empty() ? json(nullptr) : json(r.calibration_file)},
              {"calibration_restored", r.calibration_restored}};
    j["before"] = r.before ? palp::device_json(*r.before) : json(nullptr);
    j["after"] = r.after ? palp::device_json(*r.after) : json(nullptr);
    print_json(j);
  }
  return r.interrupted ? kInterrupted : kOk;
}

}  // namespace

void add_flash_command(CLI::App& app, Context& ctx) {
  auto a = std::make_shared<FlashArgs>();
  auto* cmd = app.add_subcommand(
      "flash",
      "Update the controller's firmware from IMAGE (.bin, .elf or .dfu): check the image's "
      "metadata (board, size, CRC-32, protocol) against the device before anything is erased, "
      "keep the calibration (in memory and in a file), enter the ROM DFU bootloader "
      "(EnterBootloader), erase only the image's pages, download, verify by read-back, start the "
      "new firmware, check its version and that the calibration is unchanged (written back if "
      "not). A device already in DFU mode is flashed too. Ctrl-C stops it cleanly up to the "
      "erase; a failure after the erase says how to recover (firmware/README.md, \"Flashing\"). "
      "The controller is --uri's, usb:// when neither --uri nor $PALP_URI is given");
  cmd->add_option("IMAGE", a->image, "The firmware image: .bin, .elf or .dfu (told by content)")
      ->required();
  cmd->add_flag("--dry-run", a->dry_run,
                "Print every step it would take (on stdout) and do none: only GetDeviceInfo is "
                "sent, which changes nothing");
  cmd->add_flag("--device-in-dfu", a->device_in_dfu,
                "The device already waits in its ROM DFU bootloader (USB 0483:df11): flash it "
                "without asking the controller first (its board and calibration cannot be read). "
                "Without it, a DFU device found when no controller answers is used and said so");
  cmd->add_flag("--mass-erase", a->mass_erase,
                "Erase the whole flash, the calibration's pages too (the default erases only the "
                "image's pages); the kept calibration is written back afterwards");
  cmd->add_option("--calibration-file", a->calibration_file,
                  "Where the kept calibration is written (default: IMAGE.calibration-SERIAL.json "
                  "beside the image; a file palp did not write is never replaced)");
  cmd->add_option("--dfu-serial", a->dfu_serial,
                  "The DFU device's USB serial number when several are present (default: the "
                  "first found)");
  cmd->add_option("--dfu-wait-s", a->dfu_wait_s,
                  "Wait this long for the DFU device to appear after EnterBootloader, s")
      ->check(CLI::Range(0.0, 120.0))
      ->capture_default_str();
  cmd->add_option("--reconnect-s", a->reconnect_s,
                  "Wait this long for the controller to answer after the new firmware starts, s")
      ->check(CLI::Range(0.1, 300.0))
      ->capture_default_str();
  const CLI::Option* uri = app.get_option("--uri");
  cmd->callback([&ctx, a, uri] {
    a->uri_given = uri->count() > 0 || std::getenv("PALP_URI") != nullptr;
    ctx.action = [&ctx, a] { return flash(ctx, *a); };
  });
}

}  // namespace palpctl
