#pragma once
// Fixed-size histogram of durations in microseconds: 0.1 us bins below 100 us (tick times are
// tenths of a microsecond), 1 us bins up to 20 ms (wake-up latencies), then one overflow bin;
// the exact maximum is kept. Percentiles are the upper edge of their bin, so they are exact to
// 0.1 us below 100 us and to 1 us above. Allocated once, so the loop can record every tick.
#include <cstdint>
#include <vector>

namespace palprig {

struct LatencySummary {
  double p50_us = 0, p99_us = 0, p999_us = 0, max_us = 0;
  std::uint64_t count = 0;
};

class LatencyHistogram {
 public:
  static constexpr int kFineBinsPerUs = 10;
  static constexpr int kFineLimitUs = 100;
  static constexpr int kFineBins = kFineLimitUs * kFineBinsPerUs;
  static constexpr int kLimitUs = 20000;
  static constexpr int kBins = kFineBins + (kLimitUs - kFineLimitUs);  // the overflow bin's index
  LatencyHistogram() : bins_(kBins + 1, 0) {}
  void record(double us) noexcept {
    if (!(us >= 0)) us = 0;
    const int b = us < kFineLimitUs ? static_cast<int>(us * kFineBinsPerUs)
                  : us < kLimitUs   ? kFineBins + static_cast<int>(us - kFineLimitUs)
                                    : kBins;
    ++bins_[b];
    ++count_;
    if (us > max_us_) max_us_ = us;
  }
  double percentile_us(double q) const noexcept;  // upper edge of the bin holding quantile q
  static double upper_edge_us(int bin) noexcept {
    return bin < kFineBins ? double(bin + 1) / kFineBinsPerUs : double(kFineLimitUs + (bin - kFineBins) + 1);
  }
  LatencySummary summary() const noexcept;

 private:
  std::vector<std::uint64_t> bins_;
  std::uint64_t count_ = 0;
  double max_us_ = 0;
};

}  // namespace palprig
