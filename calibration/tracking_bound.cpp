#include "calibration/tracking_bound.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace palprig {

double TrackingBound::rms_kPa() const noexcept {
  return samples ? std::sqrt(sum_squared_kPa2 / static_cast<double>(samples)) : 0.0;
}

namespace {

// Counted samples that share one z: the pressure at the block's first sample is value(), and
// through the rest of the block it decays freely (the regulator told 0 kPa).
struct Block {
  std::size_t first = 0;  // position of its first sample among the counted ones
  double t0_s = 0;        // that sample's time
  double s1 = 0;          // sum over the block of decay * target, decay = exp(-(t - t0) / tau)
  double s2 = 0;          // sum over the block of decay^2
  double value() const noexcept { return s1 / s2; }
};

}  // namespace

TrackingBound least_tracking_error(std::span<const double> t_s, std::span<const double> target_kPa,
                                   std::span<const std::uint8_t> counted, double exhaust_time_constant_s,
                                   std::vector<double>* best_kPa) {
  const std::size_t n = t_s.size();
  if (target_kPa.size() != n || counted.size() != n)
    throw Error("least tracking error: " + std::to_string(n) + " times, " + std::to_string(target_kPa.size()) +
                " targets and " + std::to_string(counted.size()) + " flags (expected one of each per sample)");
  const double tau = exhaust_time_constant_s;
  if (!(std::isfinite(tau) && tau > 0))
    throw Error("least tracking error: exhaust time constant " + std::to_string(tau) + " s (expected > 0)");
  std::vector<std::size_t> sample;  // indices of the counted samples
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(t_s[k]) || !std::isfinite(target_kPa[k]))
      throw Error("least tracking error: sample " + std::to_string(k) + " is not finite");
    if (k > 0 && !(t_s[k] > t_s[k - 1]))
      throw Error("least tracking error: time at sample " + std::to_string(k) + " does not increase");
    if (counted[k]) sample.push_back(k);
  }
  // Pool adjacent violators: a block whose start, decayed to the next block's start, lies above
  // that block's value would need the pressure to fall faster than the exhaust allows; the two
  // become one block (one z), whose best start value is the weighted mean.
  std::vector<Block> blocks;
  blocks.reserve(sample.size());
  for (std::size_t j = 0; j < sample.size(); ++j) {
    const std::size_t k = sample[j];
    Block b{j, t_s[k], target_kPa[k], 1.0};
    while (!blocks.empty()) {
      const Block prev = blocks.back();
      const double decay = std::exp(-(b.t0_s - prev.t0_s) / tau);
      if (prev.value() * decay <= b.value()) break;
      Block merged = prev;
      merged.s1 += decay * b.s1;
      merged.s2 += decay * decay * b.s2;
      blocks.pop_back();
      b = merged;
    }
    blocks.push_back(b);
  }
  TrackingBound out;
  out.samples = sample.size();
  if (best_kPa) best_kPa->assign(n, 0.0);
  for (std::size_t bi = 0; bi < blocks.size(); ++bi) {
    const Block& b = blocks[bi];
    const std::size_t end = bi + 1 < blocks.size() ? blocks[bi + 1].first : sample.size();
    const double start_kPa = b.value();
    for (std::size_t j = b.first; j < end; ++j) {
      const std::size_t k = sample[j];
      const double p = start_kPa * std::exp(-(t_s[k] - b.t0_s) / tau);
      out.sum_squared_kPa2 += (p - target_kPa[k]) * (p - target_kPa[k]);
      if (best_kPa) (*best_kPa)[k] = p;
    }
  }
  return out;
}

TrackingBound pooled(std::span<const TrackingBound> channels) noexcept {
  TrackingBound all;
  for (const TrackingBound& c : channels) {
    all.sum_squared_kPa2 += c.sum_squared_kPa2;
    all.samples += c.samples;
  }
  return all;
}

}  // namespace palprig
