#pragma once
// StatisticsError: a test cannot be computed from the data it was given (too few values, a
// constant sample, an empty group). The command line turns it into one line naming the file
// and the column, exit code 2; library callers can catch it like any invalid_argument.
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

namespace palprig::stats {

class StatisticsError : public std::invalid_argument {
 public:
  explicit StatisticsError(const std::string& what) : std::invalid_argument(what) {}
};

// The tests' first check: every value a finite number.
inline void require_finite(std::span<const double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) throw StatisticsError("a value is not a finite number");
  }
}

}  // namespace palprig::stats
