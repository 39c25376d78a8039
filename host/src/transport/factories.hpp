// SPDX-License-Identifier: Apache-2.0
// One factory per transport, each in its own file; open_transport() picks by URI scheme.
#pragma once

#include <chrono>
#include <memory>

#include "palp/transport.hpp"

namespace palp::detail {

std::unique_ptr<Transport> open_socket_transport(const Uri& uri, std::chrono::milliseconds timeout);
std::unique_ptr<Transport> open_serial_transport(const Uri& uri, std::chrono::milliseconds timeout);
std::unique_ptr<Transport> open_usb_transport(const Uri& uri, std::chrono::milliseconds timeout);
std::unique_ptr<Transport> open_hid_transport(const Uri& uri, std::chrono::milliseconds timeout);

}  // namespace palp::detail
