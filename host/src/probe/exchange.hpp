// SPDX-License-Identifier: Apache-2.0
// One request and its reply over a bare transport, outside any session: the handshake's Hello
// (session.cpp) and the frozen requests a firmware update makes before or without a session
// (GetDeviceInfo, EnterBootloader: SPEC.md §6.1; flash/update.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <variant>

#include "palp/error.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/transport.hpp"

namespace palp::detail {

/// Sends m with seq (after a 0x00 that ends any partial frame the device holds) and reads until
/// the reply with that seq comes: a Reply, or a Nak (returned as such); other frames (a stream
/// still running from before) are skipped. With `attempts` > 1 the request goes out again, with
/// the same seq, every timeout / attempts while no reply has come (only for requests that are
/// safe to repeat: Hello, GetDeviceInfo), so one lost reply costs a fraction of the timeout,
/// not the connection. Throws TimeoutError "<what> from <uri> <hint>" when none comes.
template <class Reply, class Req>
std::variant<Reply, proto::Nak> exchange(Transport& t, const Req& m, std::uint16_t seq,
                                         std::chrono::milliseconds timeout, const std::string& what,
                                         const std::string& hint = "", int attempts = 1) {
  std::array<std::uint8_t, proto::kMaxWireFrame + 1> wire{};
  const std::size_t n = proto::encode_message(m, seq, 0, wire.data() + 1, wire.size() - 1);
  proto::FrameReader reader;
  std::optional<std::variant<Reply, proto::Nak>> got;
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + timeout;
  attempts = std::max(attempts, 1);
  std::array<std::uint8_t, 4096> buf;
  for (int k = 1; k <= attempts && !got; ++k) {
    t.write(std::span<const std::uint8_t>(wire.data(), n + 1), timeout);
    const auto until = k == attempts ? deadline : start + timeout * k / attempts;
    while (!got && std::chrono::steady_clock::now() < until) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          until - std::chrono::steady_clock::now());
      const std::size_t count = t.read(buf, std::max(left, std::chrono::milliseconds(1)));
      reader.feed_messages(
          buf.data(), count,
          [&](const proto::FrameHeader& fh, const auto& r) {
            using R = std::decay_t<decltype(r)>;
            if (!(fh.flags & proto::kFlagResponse) || fh.seq != seq || got) return;
            if constexpr (std::is_same_v<R, Reply> || std::is_same_v<R, proto::Nak>) got = r;
          },
          [](proto::Reject) {});
    }
  }
  if (!got)
    throw TimeoutError(what + " from " + t.uri() + (hint.empty() ? "" : " " + hint),
                       static_cast<double>(timeout.count()) / 1000.0, std::nullopt);
  return *got;
}

}  // namespace palp::detail
