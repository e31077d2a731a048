#pragma once
// Fixed-size histogram of durations in microseconds (1 us bins up to 20 ms, then one overflow
// bin; the exact maximum is kept). Allocated once, so the loop can record every tick.
#include <cstdint>
#include <vector>

namespace palprig {

struct LatencySummary {
  double p50_us = 0, p99_us = 0, p999_us = 0, max_us = 0;
  std::uint64_t count = 0;
};

class LatencyHistogram {
 public:
  static constexpr int kBins = 20000;
  LatencyHistogram() : bins_(kBins + 1, 0) {}
  void record(double us) noexcept {
    if (!(us >= 0)) us = 0;
    const int b = us >= kBins ? kBins : static_cast<int>(us);
    ++bins_[b];
    ++count_;
    if (us > max_us_) max_us_ = us;
  }
  double percentile_us(double q) const noexcept;  // upper edge of the bin holding quantile q
  LatencySummary summary() const noexcept;

 private:
  std::vector<std::uint64_t> bins_;
  std::uint64_t count_ = 0;
  double max_us_ = 0;
};

}  // namespace palprig
