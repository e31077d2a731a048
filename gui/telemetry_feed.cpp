#include "gui/telemetry_feed.hpp"

#include <algorithm>
#include <chrono>

namespace palprig::gui {

TelemetryFeed::TelemetryFeed(std::size_t staging_capacity) : staging_capacity_(staging_capacity) {
  wake_window_.reserve(1000);
  reader_ = std::thread([this] { reader_main(); });
}

TelemetryFeed::~TelemetryFeed() {
  stop_.store(true);
  if (reader_.joinable()) reader_.join();
}

void TelemetryFeed::on_tick(const TelemetryRecord& record) noexcept {
  if (!queue_.push(record)) dropped_.fetch_add(1, std::memory_order_relaxed);
  last_t_s_.store(record.t_s, std::memory_order_release);
}

void TelemetryFeed::reader_main() {
  std::vector<TelemetryRecord> batch(1 << 12);
  while (!stop_.load()) {
    const std::size_t n = queue_.pop(batch.data(), batch.size());
    if (n == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(4));
      continue;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (reset_pending_) {
      status_ = FeedStatus{};
      wake_window_.clear();
      wake_next_ = 0;
      second_of_ticks_.clear();
      reset_pending_ = false;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const TelemetryRecord& r = batch[i];
      if (staged_.size() >= staging_capacity_) staged_.pop_front();  // the GUI stalled: keep the newest
      staged_.push_back(trace_sample_of(r));
      ++status_.ticks;
      if (r.flags & kOverrun) ++status_.overruns;
      if (wake_window_.size() < 1000)
        wake_window_.push_back(r.wake_latency_us);
      else
        wake_window_[wake_next_] = r.wake_latency_us;
      wake_next_ = (wake_next_ + 1) % 1000;
      second_of_ticks_.push_back(r.t_s);
      while (!second_of_ticks_.empty() && second_of_ticks_.front() <= r.t_s - 1.0) second_of_ticks_.pop_front();
    }
    status_.latest = batch[n - 1];
    status_.have_record = true;
    // Ticks in the last second of loop time; before a full second has passed, scale up.
    const double span = second_of_ticks_.size() > 1 ? second_of_ticks_.back() - second_of_ticks_.front() : 0.0;
    status_.loop_rate_hz = span > 0 ? double(second_of_ticks_.size() - 1) / span : 0.0;
    std::vector<float> sorted(wake_window_);
    if (!sorted.empty()) {
      auto pct = [&](double q) {
        const auto k = std::size_t(q * double(sorted.size() - 1));
        std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
        return double(sorted[k]);
      };
      status_.wake_p50_us = pct(0.50);
      status_.wake_p99_us = pct(0.99);
    }
  }
}

FeedStatus TelemetryFeed::take(std::vector<TraceSample>& into) {
  std::lock_guard<std::mutex> lock(mutex_);
  into.insert(into.end(), staged_.begin(), staged_.end());
  staged_.clear();
  FeedStatus s = status_;
  s.dropped = dropped_.load(std::memory_order_relaxed);
  return s;
}

void TelemetryFeed::reset_statistics() {
  std::lock_guard<std::mutex> lock(mutex_);
  reset_pending_ = true;
  staged_.clear();
  status_.have_record = false;
}

}  // namespace palprig::gui
