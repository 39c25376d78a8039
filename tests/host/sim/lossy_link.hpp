// SPDX-License-Identifier: Apache-2.0
// A Transport between the Probe and the in-process simulator that loses chosen replies (or events) and
// records every request the host sent: the lost reply of issue 17 (item 2) made exact, where
// palp-sim's drop-frames loses every n-th device frame whatever it is.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "palp/protocol/frame.hpp"
#include "palp/transport.hpp"

namespace palp::test {

class LossyLink : public Transport {
 public:
  struct Sent {
    proto::MessageId id;
    std::uint16_t seq;
  };
  /// Shared with the test while the Probe owns the link.
  struct Log {
    std::mutex mu;
    std::vector<Sent> sent;  ///< every request frame the host wrote, in order
    /// Decides for each reply (response flag set) whether it is lost: (request id, seq) -> lose.
    /// Runs on the Probe's I/O thread.
    std::function<bool(proto::MessageId, std::uint16_t)> lose;
    /// The same for a device-originated frame (an event, a sample batch), by its message id.
    std::function<bool(proto::MessageId)> lose_unasked;
    int lost = 0;
    /// The request the reply with this seq answers (the last one sent with it).
    proto::MessageId request_of(std::uint16_t seq) {
      for (auto it = sent.rbegin(); it != sent.rend(); ++it)
        if (it->seq == seq) return it->id;
      return proto::MessageId::None;
    }
    int copies(proto::MessageId id, std::uint16_t seq) {
      int n = 0;
      for (const Sent& s : sent) n += s.id == id && s.seq == seq;
      return n;
    }
  };

  LossyLink(std::unique_ptr<Transport> inner, std::shared_ptr<Log> log)
      : inner_(std::move(inner)), log_(std::move(log)) {}

  void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) override {
    to_device_.feed(bytes.data(), bytes.size(), [&](const proto::Frame& f) {
      std::lock_guard lock(log_->mu);
      log_->sent.push_back({static_cast<proto::MessageId>(f.header.id), f.header.seq});
    }, [](proto::Reject) {});
    inner_->write(bytes, timeout);
  }

  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) override {
    if (ready_.empty()) {
      std::uint8_t in[4096];
      const std::size_t n = inner_->read(std::span<std::uint8_t>(in, sizeof in), timeout);
      for (std::size_t k = 0; k < n; ++k) {
        partial_.push_back(in[k]);
        if (in[k] == 0) pass_or_lose_frame();
      }
    }
    const std::size_t n = std::min(buf.size(), ready_.size());
    std::copy(ready_.begin(), ready_.begin() + static_cast<long>(n), buf.begin());
    ready_.erase(ready_.begin(), ready_.begin() + static_cast<long>(n));
    return n;
  }

  std::uint32_t max_device_bytes_per_s() const override { return inner_->max_device_bytes_per_s(); }
  const std::string& uri() const override { return inner_->uri(); }

 private:
  void pass_or_lose_frame() {
    bool lose = false;
    proto::FrameReader one;
    one.feed(partial_.data(), partial_.size(), [&](const proto::Frame& f) {
      std::lock_guard lock(log_->mu);
      if ((f.header.flags & proto::kFlagResponse) == 0)
        lose = log_->lose_unasked && log_->lose_unasked(static_cast<proto::MessageId>(f.header.id));
      else
        lose = log_->lose && log_->lose(log_->request_of(f.header.seq), f.header.seq);
      log_->lost += lose;
    }, [](proto::Reject) {});
    if (!lose) ready_.insert(ready_.end(), partial_.begin(), partial_.end());
    partial_.clear();
  }

  std::unique_ptr<Transport> inner_;
  std::shared_ptr<Log> log_;
  proto::FrameReader to_device_;
  std::vector<std::uint8_t> partial_, ready_;
};

}  // namespace palp::test
