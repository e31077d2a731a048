#pragma once
// RandomSource: the one generator behind trial orders and simulated participants. The standard
// library's distributions differ between implementations, and a stored seed must regenerate
// the same order on any machine, so the generator (xoshiro256**, seeded through SplitMix64)
// and every distribution used are written out here.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace palprig {

class RandomSource {
 public:
  explicit RandomSource(std::uint64_t seed) noexcept;

  std::uint64_t next() noexcept;
  // Uniform integer in [0, bound) without modulo bias (Lemire's multiply-and-reject). bound > 0.
  std::uint64_t below(std::uint64_t bound) noexcept;
  // Uniform double in [0, 1) with 53 random bits.
  double uniform() noexcept;
  // Standard normal (Marsaglia's polar method).
  double normal() noexcept;
  // Log-normal with the given mean and standard deviation of the variable itself (not of its log).
  double lognormal_with_mean_sd(double mean, double sd) noexcept;

 private:
  std::uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0;
};

// A stable 64-bit hash of a text (FNV-1a), e.g. to derive a session seed from a participant code.
std::uint64_t stable_hash(std::string_view text) noexcept;

}  // namespace palprig
