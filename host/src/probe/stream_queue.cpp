#include "probe/stream_queue.hpp"

#include <algorithm>

namespace palp::detail {

void StreamQueue::deliver_locked(StreamItem&& item) {
  if (callback_) {
    callback_(item);
    return;
  }
  items_.push_back(std::move(item));
  max_depth_ = std::max<std::uint64_t>(max_depth_, items_.size());
}

void StreamQueue::flush_drop_locked() {
  if (!drop_) return;
  ++gaps_;
  missing_ += drop_->count;
  deliver_locked(StreamItem(*drop_));
  drop_.reset();
}

void StreamQueue::push(std::vector<StreamItem>& batch) {
  {
    std::lock_guard lock(mu_);
    for (StreamItem& item : batch) {
      if (const Sample* s = std::get_if<Sample>(&item)) {
        if (!callback_ && items_.size() >= capacity_) {
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
        flush_drop_locked();
        ++samples_;
        deliver_locked(std::move(item));
      } else {
        flush_drop_locked();
        const Gap& g = std::get<Gap>(item);
        ++gaps_;
        missing_ += g.count;
        deliver_locked(std::move(item));
      }
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
  std::lock_guard lock(mu_);
  callback_ = std::move(cb);
  if (callback_) {
    flush_drop_locked();
    while (!items_.empty()) {  // what was queued goes out first, in order
      callback_(items_.front());
      items_.pop_front();
    }
  }
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
