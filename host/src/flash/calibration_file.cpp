// SPDX-License-Identifier: Apache-2.0
// The kept calibration's file (calibration_file.hpp).
#include "flash/calibration_file.hpp"

#include <array>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "palp/error.hpp"
#include "palp/protocol/codec.hpp"
#include "palp/protocol/text.hpp"
#include "palp/result.hpp"

namespace palp::flash::detail {

namespace fs = std::filesystem;

std::string default_calibration_path(const std::string& image_path, const std::string& serial) {
  std::string safe = serial.empty() ? "unknown" : serial;
  for (char& c : safe)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return image_path + ".calibration-" + safe + ".json";
}

void check_calibration_path(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object() || j.value("palp_file", std::string()) != kCalibrationFileKind)
    throw ConfigError(path + " exists and palp did not write it: nothing was changed; move it "
                             "away or name another file for the calibration (--calibration-file)");
}

std::vector<std::uint8_t> calibration_bytes(const Calibration& c) {
  std::array<std::uint8_t, proto::max_payload_size<proto::Calibration>()> buf{};
  const int n = proto::encode_payload(c, buf.data(), buf.size());
  return {buf.begin(), buf.begin() + (n > 0 ? n : 0)};
}

void write_calibration_file(const std::string& path, const Calibration& c, const DeviceInfo& device,
                            const std::string& image_path) {
  check_calibration_path(path);
  const nlohmann::json j = {
      {"palp_file", kCalibrationFileKind},
      {"what", "the calibration palp read from the device before a firmware update"},
      {"device", {{"serial", device.serial}, {"board", device.board},
                  {"firmware_version", device.firmware_version}, {"git_hash", device.git_hash}}},
      {"image", image_path},
      {"calibration", calibration_json(c)},
      {"calibration_payload_hex", proto::to_hex(calibration_bytes(c))}};
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << j.dump(2) << '\n';
    if (!out) throw ConfigError("cannot write the calibration to " + tmp + ": nothing was changed");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec)
    throw ConfigError("cannot write the calibration to " + path + " (" + ec.message() +
                      "): nothing was changed");
}

}  // namespace palp::flash::detail
