// SPDX-License-Identifier: Apache-2.0
#include "probe/stream_queue.hpp"

#include <algorithm>
#include <string>

#include "probe/log.hpp"

namespace palp::detail {

void StreamQueue::deliver_locked(StreamItem&& item) {
  items_.push_back(std::move(item));
  max_depth_ = std::max<std::uint64_t>(max_depth_, items_.size());
}

void StreamQueue::flush_drop_locked() {
  if (!drop_) return;
  StreamItem gap(*drop_);
  count_item_locked(gap);
  deliver_locked(std::move(gap));
  drop_.reset();
}

void StreamQueue::count_item_locked(const StreamItem& item) {
  if (std::holds_alternative<Sample>(item)) {
    ++samples_;
  } else {
    const Gap& g = std::get<Gap>(item);
    ++gaps_;
    missing_ += g.count;
    if (logging())
      log(LogLevel::warning, "stream gap: " + (g.count_known ? std::to_string(g.count) : std::string("an unknown number of")) +
                                 " samples missing from index " + std::to_string(g.first_index) + " (" +
                                 gap_source_name(g.source) + ")");
  }
}

void StreamQueue::push(std::vector<StreamItem>& batch) {
  std::lock_guard cb_lock(cb_mu_);
  std::function<void(const StreamItem&)> cb;
  {
    std::lock_guard lock(mu_);
    cb = callback_;
    if (cb)
      for (const StreamItem& item : batch) count_item_locked(item);
  }
  if (cb) {  // on the I/O thread, outside the queue's lock
    for (const StreamItem& item : batch) cb(item);
    batch.clear();
    return;
  }
  {
    std::lock_guard lock(mu_);
    for (StreamItem& item : batch) {
      if (const Sample* s = std::get_if<Sample>(&item)) {
        if (items_.size() >= capacity_) {
          if (!drop_) {
            drop_ = Gap{};
            drop_->first_index = s->index;
            drop_->source = GapSource::host_queue;
            drop_->t_device_s = s->t_device_s;
          }
          ++drop_->count;
          ++dropped_;
          continue;
        }
      }
      flush_drop_locked();
      count_item_locked(item);
      deliver_locked(std::move(item));
    }
  }
  batch.clear();
  cv_.notify_all();
}

std::optional<StreamItem> StreamQueue::pop(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mu_);
  if (!cv_.wait_for(lock, timeout, [&] { return !items_.empty() || drop_.has_value(); }))
    return std::nullopt;
  if (items_.empty()) flush_drop_locked();  // the drop run ends once the consumer catches up
  StreamItem item = std::move(items_.front());
  items_.pop_front();
  return item;
}

std::size_t StreamQueue::drain(std::vector<StreamItem>& out, std::size_t max) {
  std::lock_guard lock(mu_);
  std::size_t n = 0;
  while (n < max) {
    if (items_.empty()) {
      if (!drop_) break;
      flush_drop_locked();
    }
    out.push_back(std::move(items_.front()));
    items_.pop_front();
    ++n;
  }
  return n;
}

void StreamQueue::set_callback(std::function<void(const StreamItem&)> cb) {
  std::lock_guard cb_lock(cb_mu_);  // no push runs meanwhile: order is kept
  std::deque<StreamItem> queued;
  {
    std::lock_guard lock(mu_);
    callback_ = cb;
    if (!callback_) return;
    flush_drop_locked();
    queued.swap(items_);
  }
  for (const StreamItem& item : queued) cb(item);  // what was queued goes out first, in order
}

void StreamQueue::clear() {
  std::lock_guard lock(mu_);
  items_.clear();
  drop_.reset();
}

void StreamQueue::count_into(HealthCounters& h) const {
  std::lock_guard lock(mu_);
  h.host_samples_received = samples_ + dropped_;
  h.host_samples_missing = missing_ + (drop_ ? drop_->count : 0);
  h.host_queue_dropped = dropped_;
  h.host_queue_max = max_depth_;
  h.host_gaps = gaps_;
}

}  // namespace palp::detail
