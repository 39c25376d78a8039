// SPDX-License-Identifier: Apache-2.0
// Probe's private state (probe.cpp, probe_helpers.cpp).
#pragma once

#include <memory>
#include <vector>

#include "palp/probe.hpp"
#include "probe/session.hpp"

namespace palp {

namespace detail {
/// The public DeviceInfo of the protocol's message.
DeviceInfo device_info_from(const proto::DeviceInfo& d);
}  // namespace detail

struct Probe::Impl {
  std::unique_ptr<detail::Session> session;
  DeviceInfo info;  // kept, with the handshake and the URI, so they outlive close()
  Handshake handshake;
  std::string uri;
  StreamInfo stream;
  std::uint64_t finished_before_start = 0;
  std::uint64_t contact_before_start = 0;
  std::vector<ZeroingRecord> zeroing;
  detail::Session& s();
};

}  // namespace palp
