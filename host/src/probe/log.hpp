// SPDX-License-Identifier: Apache-2.0
// The SDK's side of palp/log.hpp: report a line through the program's handler, if any.
#pragma once

#include <string>

#include "palp/log.hpp"

namespace palp::detail {

/// Whether a handler is installed (to skip building a message nobody reads).
bool logging();
/// Hands the line to the handler; a handler that throws is ignored.
void log(LogLevel level, const std::string& message);

}  // namespace palp::detail
