#pragma once
// TelemetryFeed: the loop's records on their way to the window. The loop thread hands every
// record to on_tick(), which only pushes it into a wait-free single-producer queue (dropping,
// and counting, when the queue is full: the loop never waits for the GUI). A reader thread
// drains the queue every few milliseconds into a bounded staging list and keeps the running
// statistics the status bar shows; the GUI's poll timer takes the staged samples. The only lock
// is between the reader thread and the GUI thread; the loop never touches it.
#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include <boost/lockfree/spsc_queue.hpp>

#include "controller/loop_runner.hpp"
#include "gui/trace_history.hpp"

namespace palprig::gui {

struct FeedStatus {
  bool have_record = false;
  TelemetryRecord latest;                   // newest record seen
  double loop_rate_hz = 0;                  // ticks per second over the last second of loop time
  std::uint64_t ticks = 0;                  // records seen
  std::uint64_t overruns = 0;               // records flagged overrun
  double wake_p50_us = 0, wake_p99_us = 0;  // over the last 1000 ticks (real-time runs)
  std::uint64_t dropped = 0;                // records the loop could not queue
};

class TelemetryFeed final : public TickObserver {
 public:
  explicit TelemetryFeed(std::size_t staging_capacity = 60000);
  ~TelemetryFeed() override;
  TelemetryFeed(const TelemetryFeed&) = delete;
  TelemetryFeed& operator=(const TelemetryFeed&) = delete;

  // Loop thread: wait-free, never allocates.
  void on_tick(const TelemetryRecord& record) noexcept override;

  // Any thread: loop time of the last tick the loop finished (tests check what came after).
  double last_t_s() const noexcept { return last_t_s_.load(std::memory_order_acquire); }

  // GUI thread: the samples staged since the last call (appended to `into`) and the status.
  FeedStatus take(std::vector<TraceSample>& into);
  // Forget the statistics (a new run starts).
  void reset_statistics();

 private:
  void reader_main();

  boost::lockfree::spsc_queue<TelemetryRecord, boost::lockfree::capacity<1 << 14>> queue_;
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<double> last_t_s_{0};
  std::atomic<bool> stop_{false};

  std::mutex mutex_;  // reader thread <-> GUI thread only
  std::deque<TraceSample> staged_;
  std::size_t staging_capacity_;
  FeedStatus status_;
  std::vector<float> wake_window_;  // last 1000 wake-up latencies (ring)
  std::size_t wake_next_ = 0;
  std::deque<double> second_of_ticks_;  // loop times of the last second's ticks
  bool reset_pending_ = false;

  std::thread reader_;
};

}  // namespace palprig::gui
