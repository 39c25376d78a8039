// SPDX-License-Identifier: Apache-2.0
// Reading the two phantom kinds from a parsed file (keys: README.md "Phantom files").
// Private to palp_plant.
#pragma once

#include <memory>

#include "key_value_file.hpp"
#include "palp/plant/phantom.hpp"

namespace palp::plant::detail {

std::shared_ptr<const Phantom> read_line_phantom(const KeyValueFile& file);
std::shared_ptr<const Phantom> read_pad_phantom(const KeyValueFile& file);

}  // namespace palp::plant::detail
