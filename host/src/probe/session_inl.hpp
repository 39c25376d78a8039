// Session's templates (included by session.hpp).
#pragma once

#include <array>

#include "palp/error.hpp"

namespace palp::detail {

/// "LoadRamp refused: out_of_range (a field is outside its range), field step_A" and friends.
std::string nak_text(const char* request, const proto::FieldInfo* fields, std::size_t nfields,
                     const proto::Nak& nak);

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
  std::lock_guard rl(request_mu_);
  const auto deadline = Clock::now() + timeout;
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
  try {
    write_message(m, seq);
  } catch (...) {
    std::lock_guard lock(mu_);
    waiting_seq_.reset();
    throw;
  }
  std::unique_lock lock(mu_);
  const bool got =
      cv_.wait_until(lock, deadline, [&] { return reply_ready_ || !reply_error_.empty(); });
  waiting_seq_.reset();
  if (!reply_error_.empty()) throw ConnectionError(reply_error_);
  if (!got) {
    lock.unlock();
    throw_timeout(std::string("the reply to ") + Req::kName, timeout);
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
