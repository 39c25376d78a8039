// SPDX-License-Identifier: Apache-2.0
#include "probe/stream_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "palp/error.hpp"
#include "palp/protocol/stream.hpp"

namespace palp::detail {
namespace {
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}
}  // namespace

proto::StreamConfigure check_stream(const StreamSettings& st, double control_rate_Hz,
                                    double max_rate_Hz, std::uint32_t transport_bytes_per_s,
                                    const std::string& uri) {
  if (!(st.rate_Hz > 0) || st.rate_Hz > max_rate_Hz)
    throw ConfigError("stream rate " + num(st.rate_Hz) + " Hz is outside (0, " + num(max_rate_Hz) +
                      "] Hz, the device's range");
  const double dec = control_rate_Hz / st.rate_Hz;
  const double whole = std::round(dec);
  if (std::fabs(dec - whole) > 1e-9 * dec || whole > 65535)
    throw ConfigError("stream rate " + num(st.rate_Hz) + " Hz does not divide the control rate " +
                      num(control_rate_Hz) + " Hz (nearest: " +
                      num(control_rate_Hz / std::ceil(dec)) + " Hz or " +
                      num(control_rate_Hz / std::max(1.0, std::floor(dec))) + " Hz)");
  if (st.channels == 0 || (st.channels & ~channel::all) != 0) {
    char b[8];
    std::snprintf(b, sizeof b, "0x%04x", st.channels);
    throw ConfigError(std::string("stream channels ") + b +
                      ": choose one or more of the 11 channel bits (palp::channel)");
  }
  const std::size_t most = proto::max_batch_samples(st.channels);
  std::size_t batch = st.batch_samples;
  if (batch == 0)  // about 25 batches a second, whole batches only
    batch = std::clamp<std::size_t>(static_cast<std::size_t>(st.rate_Hz / 25.0), 1, most);
  if (batch > most)
    throw ConfigError("stream batch of " + std::to_string(batch) + " samples: at most " +
                      std::to_string(most) + " samples of " +
                      std::to_string(proto::bytes_per_sample(st.channels)) +
                      " bytes fit one batch");
  const std::uint32_t need = proto::stream_wire_bytes_per_s(st.channels, st.rate_Hz, batch);
  if (need > transport_bytes_per_s)
    throw ConfigError("stream of " + std::to_string(proto::bytes_per_sample(st.channels)) +
                      "-byte samples at " + num(st.rate_Hz) + " Hz needs " + std::to_string(need) +
                      " bytes/s on the wire, but " + uri + " carries at most " +
                      std::to_string(transport_bytes_per_s) +
                      " bytes/s: lower the rate or stream fewer channels");
  proto::StreamConfigure c;
  c.channels = st.channels;
  c.decimation = static_cast<std::uint16_t>(whole);
  c.batch_samples = static_cast<std::uint16_t>(batch);
  return c;
}

}  // namespace palp::detail
