#include "runtime/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

double LatencyHistogram::percentile_us(double q) const noexcept {
  if (count_ == 0) return 0;
  const auto rank = static_cast<std::uint64_t>(std::ceil(q * double(count_)));
  std::uint64_t seen = 0;
  for (int b = 0; b <= kBins; ++b) {
    seen += bins_[b];
    if (seen >= std::max<std::uint64_t>(rank, 1)) return b == kBins ? max_us_ : std::min(upper_edge_us(b), max_us_);
  }
  return max_us_;
}

LatencySummary LatencyHistogram::summary() const noexcept {
  return {percentile_us(0.5), percentile_us(0.99), percentile_us(0.999), max_us_, count_};
}

}  // namespace palprig
