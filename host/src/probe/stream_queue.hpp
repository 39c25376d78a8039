// SPDX-License-Identifier: Apache-2.0
// The bounded queue between the probe's I/O thread and the application (probe.hpp describes the
// back-pressure policy): samples beyond the capacity are dropped and become one host_queue Gap,
// delivered in order as soon as there is room; gap records are never dropped.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "palp/health.hpp"
#include "palp/stream.hpp"

namespace palp::detail {

class StreamQueue {
 public:
  explicit StreamQueue(std::size_t capacity) : capacity_(capacity == 0 ? 1 : capacity) {}

  /// I/O thread: never blocks.
  void push(std::vector<StreamItem>& items);
  std::optional<StreamItem> pop(std::chrono::milliseconds timeout);
  std::size_t drain(std::vector<StreamItem>& out, std::size_t max);
  void set_callback(std::function<void(const StreamItem&)> cb);
  void clear();
  /// Adds the host-side counters to h.
  void count_into(HealthCounters& h) const;

 private:
  void flush_drop_locked();
  void deliver_locked(StreamItem&& item);
  void count_item_locked(const StreamItem& item);

  std::size_t capacity_;
  // callback delivery happens under cb_mu_ only, never under mu_: a callback may take its own
  // locks while another thread waits in pop() (which takes mu_ alone)
  std::mutex cb_mu_;
  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::deque<StreamItem> items_;
  std::function<void(const StreamItem&)> callback_;
  std::optional<Gap> drop_;  // the open run of dropped samples
  std::uint64_t samples_ = 0, missing_ = 0, dropped_ = 0, max_depth_ = 0, gaps_ = 0;
};

}  // namespace palp::detail
