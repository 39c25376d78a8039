// SPDX-License-Identifier: Apache-2.0
// Session's templates (included by session.hpp).
#pragma once

#include <array>
#include <cmath>
#include <type_traits>

#include "palp/error.hpp"
#include "probe/log.hpp"

namespace palp::detail {

/// "LoadRamp refused: out_of_range (a field is outside its range), field step_A" and friends.
std::string nak_text(const char* request, const proto::FieldInfo* fields, std::size_t nfields,
                     const proto::Nak& nak);

/// ConfigError "LoadHold: current_A is nan, not a finite number; nothing was sent" for a
/// floating-point field (or element) that is NaN or infinite. The device refuses such a field
/// too (out_of_range, §5.5); the SDK refuses it first, by its catalogue name.
template <class M>
void require_finite_fields(const M& m) {
  m.visit([](const proto::FieldInfo& f, const auto& value) {
    using V = std::remove_cvref_t<decltype(value)>;
    auto check = [&](auto x, std::size_t element, bool many) {
      if constexpr (std::is_floating_point_v<decltype(x)>) {
        if (std::isfinite(x)) return;
        throw ConfigError(std::string(M::kName) + ": " + f.name +
                          (many ? "[" + std::to_string(element) + "]" : std::string()) + " is " +
                          (std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf") +
                          ", not a finite number; nothing was sent");
      }
    };
    if constexpr (std::is_floating_point_v<V>) {
      check(value, 0, false);
    } else if constexpr (requires { value.items; }) {
      for (std::size_t k = 0; k < value.size && k < value.items.size(); ++k) check(value.items[k], k, true);
    } else if constexpr (requires { value.bytes; }) {
      // text
    } else if constexpr (requires { value.size(); value[0]; }) {
      for (std::size_t k = 0; k < value.size(); ++k) check(value[k], k, true);
    }
  });
}

template <class M>
void Session::write_message(const M& m, std::uint16_t seq) {
  std::array<std::uint8_t, proto::kMaxWireFrame> wire;
  const std::size_t n = proto::encode_message(m, seq, 0, wire.data(), wire.size());
  if (n == 0) throw ConfigError(std::string(M::kName) + ": the message does not fit one frame");
  std::shared_ptr<Transport> t;
  {
    std::lock_guard lock(mu_);
    t = transport_;
  }
  if (!t) throw ConnectionError("the link to " + uri_ + " was lost");
  std::lock_guard wl(write_mu_);
  t->write(std::span<const std::uint8_t>(wire.data(), n), options_.timeout);
}

template <class M>
std::uint16_t Session::send_async(const M& m, AsyncKind kind) {
  const std::uint16_t seq = seq_++;
  {
    std::lock_guard lock(mu_);
    async_[seq] = Async{kind, now_s()};
    if (async_.size() > 256) async_.erase(async_.begin());  // replies that never came
  }
  write_message(m, seq);
  return seq;
}

template <class Req>
Reply Session::request(const Req& m, std::chrono::milliseconds timeout) {
  require_finite_fields(m);
  std::lock_guard rl(request_mu_);
  const auto start = Clock::now();
  const auto deadline = start + timeout;
  std::uint16_t seq = 0;
  {
    std::unique_lock lock(mu_);
    const bool up = cv_.wait_until(lock, deadline, [&] { return link_up_ || !dead_.empty(); });
    if (!dead_.empty()) throw ConnectionError(dead_);
    if (!up) {
      lock.unlock();
      throw_timeout(std::string("the link to be restored before sending ") + Req::kName, timeout);
    }
    seq = seq_++;
    waiting_seq_ = seq;
    reply_ready_ = false;
    reply_error_.clear();
  }
  auto forget = [&] {
    std::lock_guard lock(mu_);
    waiting_seq_.reset();
  };
  try {
    write_message(m, seq);
  } catch (...) {
    forget();
    throw;
  }
  // a resendable request whose reply is lost goes out again with the same seq at every
  // timeout / kSendAttempts; a reply to any of the copies answers it (session.hpp)
  const int attempts = kResendable<Req> ? kSendAttempts : 1;
  std::unique_lock lock(mu_);
  bool got = false;
  for (int a = 1;; ++a) {
    const auto until = a < attempts ? start + timeout * a / attempts : deadline;
    got = cv_.wait_until(lock, until, [&] { return reply_ready_ || !reply_error_.empty(); });
    if (got || a >= attempts) break;
    ++resends_;
    lock.unlock();
    detail::log(LogLevel::warning, std::string("no reply to ") + Req::kName + " from " + uri_ + " within " +
                                       std::to_string((timeout / attempts).count()) + " ms: resent it");
    try {
      write_message(m, seq);
    } catch (const TimeoutError&) {
      // the copy could not go out in time: the next attempt (or the deadline) decides
    } catch (...) {
      forget();
      throw;
    }
    lock.lock();
  }
  waiting_seq_.reset();
  if (!reply_error_.empty()) throw ConnectionError(reply_error_);
  if (!got) {
    lock.unlock();
    throw_timeout(std::string("the reply to ") + Req::kName +
                      (attempts > 1 ? " (sent " + std::to_string(attempts) + " times with seq " +
                                          std::to_string(seq) + ")"
                                    : std::string()),
                  timeout);
  }
  Reply r = std::move(reply_);
  reply_ready_ = false;
  lock.unlock();
  if (const auto* nak = std::get_if<proto::Nak>(&r))
    throw DeviceError(nak_text(Req::kName, Req::kFields.data(), Req::kFields.size(), *nak),
                      Req::kName, static_cast<std::uint16_t>(nak->error), nak->field_index,
                      nak->detail);
  return r;
}

template <class Pred>
bool Session::wait_event(std::chrono::milliseconds timeout, Pred&& pred) {
  std::unique_lock lock(mu_);
  const bool ok = cv_.wait_for(lock, timeout, [&] { return pred(events_) || !dead_.empty(); });
  if (!dead_.empty() && !pred(events_)) throw ConnectionError(dead_);
  return ok;
}

}  // namespace palp::detail
