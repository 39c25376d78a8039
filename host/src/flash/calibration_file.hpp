// SPDX-License-Identifier: Apache-2.0
// The calibration a firmware update keeps, as a file (palp/flash.hpp, step 3): the device's
// Calibration message byte for byte (hex) and in lab units, marked as palp's so a later update
// may replace it, and nothing else is ever overwritten.
#pragma once

#include <string>

#include "palp/probe.hpp"

namespace palp::flash::detail {

/// The value of the file's "palp_file" key.
inline constexpr const char* kCalibrationFileKind = "flash-calibration";

/// IMAGE.calibration-SERIAL.json (the serial's characters other than letters, digits, '-' and
/// '_' as '_').
std::string default_calibration_path(const std::string& image_path, const std::string& serial);

/// Throws ConfigError when path exists and is not a file this code wrote (no "palp_file":
/// "flash-calibration" in a JSON object), naming it; nothing is written.
void check_calibration_path(const std::string& path);

/// Writes the file (through a temporary file and a rename); ConfigError when it cannot.
void write_calibration_file(const std::string& path, const Calibration& c, const DeviceInfo& device,
                            const std::string& image_path);

/// The Calibration message's payload bytes: two calibrations are equal when these are.
std::vector<std::uint8_t> calibration_bytes(const Calibration& c);

}  // namespace palp::flash::detail
