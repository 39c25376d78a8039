// SPDX-License-Identifier: Apache-2.0
// Checks a stream request against the device and the transport before anything is sent, and
// turns it into the StreamConfigure the device gets (probe.hpp, configure_stream).
#pragma once

#include <string>

#include "palp/protocol/messages.hpp"
#include "palp/stream.hpp"

namespace palp::detail {

/// Throws ConfigError naming the numbers when: the rate is not in (0, max_rate_Hz] or does not
/// divide control_rate_Hz; no or unknown channels; the batch does not fit one SampleBatch; or
/// the encoded stream needs more bytes per second than the transport carries.
proto::StreamConfigure check_stream(const StreamSettings& s, double control_rate_Hz,
                                    double max_rate_Hz, std::uint32_t transport_bytes_per_s,
                                    const std::string& uri);

}  // namespace palp::detail
