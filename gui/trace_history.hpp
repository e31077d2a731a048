#pragma once
// TraceHistory: the last N ticks of what each finger was asked for, sent and got (target,
// setpoint, monitor), at the loop's full rate, for the live strip chart. A ring buffer owned by
// the GUI thread; columns_min_max() reduces a time window to one (min, max) pair per pixel
// column, which is what the chart draws (see strip_chart.hpp for why).
#include <array>
#include <cstddef>
#include <vector>

#include "controller/telemetry.hpp"

namespace palprig::gui {

enum class TraceKind { target = 0, setpoint = 1, monitor = 2 };
inline constexpr int kTraceKinds = 3;

struct TraceSample {
  double t_s = 0;
  float kPa[kTraceKinds][kFingerCount] = {};  // [TraceKind][finger]
};

TraceSample trace_sample_of(const TelemetryRecord& r) noexcept;

// One pixel column: the lowest and highest value among the samples whose time falls in it;
// empty when none does.
struct ColumnExtent {
  float min = 0, max = 0;
  bool empty = true;
};

class TraceHistory {
 public:
  explicit TraceHistory(std::size_t capacity);
  void push(const TraceSample& s) noexcept;  // overwrites the oldest when full
  void clear() noexcept {
    size_ = 0;
    head_ = 0;
  }
  std::size_t size() const noexcept { return size_; }
  std::size_t capacity() const noexcept { return ring_.size(); }
  const TraceSample& at(std::size_t i) const noexcept;  // 0 = oldest
  const TraceSample& newest() const noexcept { return at(size_ - 1); }

  // The window [t0_s, t1_s) split into `columns` equal columns; `out` is resized to columns.
  // One pass over the samples in the window (binary search for its start).
  void columns_min_max(TraceKind kind, int finger, double t0_s, double t1_s, int columns,
                       std::vector<ColumnExtent>& out) const;

 private:
  std::vector<TraceSample> ring_;
  std::size_t head_ = 0;  // index of the oldest sample
  std::size_t size_ = 0;
};

}  // namespace palprig::gui
