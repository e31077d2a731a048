#include "gui/trace_history.hpp"

#include <algorithm>
#include <cmath>

namespace palprig::gui {

TraceSample trace_sample_of(const TelemetryRecord& r) noexcept {
  TraceSample s;
  s.t_s = r.t_s;
  for (int i = 0; i < kFingerCount; ++i) {
    s.kPa[int(TraceKind::target)][i] = r.target_kPa[i];
    s.kPa[int(TraceKind::setpoint)][i] = r.setpoint_kPa[i];
    s.kPa[int(TraceKind::monitor)][i] = r.monitor_kPa[i];
  }
  return s;
}

TraceHistory::TraceHistory(std::size_t capacity) : ring_(std::max<std::size_t>(capacity, 1)) {}

void TraceHistory::push(const TraceSample& s) noexcept {
  if (size_ < ring_.size()) {
    ring_[(head_ + size_) % ring_.size()] = s;
    ++size_;
  } else {
    ring_[head_] = s;
    head_ = (head_ + 1) % ring_.size();
  }
}

const TraceSample& TraceHistory::at(std::size_t i) const noexcept { return ring_[(head_ + i) % ring_.size()]; }

void TraceHistory::columns_min_max(TraceKind kind, int finger, double t0_s, double t1_s, int columns,
                                   std::vector<ColumnExtent>& out) const {
  out.assign(static_cast<std::size_t>(std::max(columns, 0)), ColumnExtent{});
  if (columns <= 0 || !(t1_s > t0_s) || size_ == 0) return;
  // First sample at or after t0 (times only grow within a run; clear() starts a new one).
  std::size_t lo = 0, hi = size_;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (at(mid).t_s < t0_s)
      lo = mid + 1;
    else
      hi = mid;
  }
  const double per_column = double(columns) / (t1_s - t0_s);
  const int k = int(kind);
  for (std::size_t i = lo; i < size_; ++i) {
    const TraceSample& s = at(i);
    if (s.t_s >= t1_s) break;
    const float v = s.kPa[k][finger];
    if (!std::isfinite(v)) continue;  // a monitor with no reading (link down) is a gap
    const int c = std::min(columns - 1, int((s.t_s - t0_s) * per_column));
    ColumnExtent& e = out[std::size_t(c)];
    if (e.empty) {
      e.min = e.max = v;
      e.empty = false;
    } else {
      e.min = std::min(e.min, v);
      e.max = std::max(e.max, v);
    }
  }
}

}  // namespace palprig::gui
