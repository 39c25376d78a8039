// SPDX-License-Identifier: Apache-2.0
// Internal to the DfuSe client: text helpers shared by its files.
#pragma once

#include <cstdint>
#include <string>

namespace palp::dfu::internal {

/// What a status code means, for a message ("the flash could not be written").
std::string status_meaning(std::uint8_t status);
/// "0x08000800".
std::string hex32(std::uint32_t value);

}  // namespace palp::dfu::internal
