#pragma once
// StatisticsError: a test cannot be computed from the data it was given (too few values, a
// constant sample, an empty group). It is a BadInput (core/error.hpp): the command line turns it
// into one line naming the file and the column, exit code 2.
#include <cmath>
#include <span>
#include <string>

#include "core/error.hpp"

namespace palprig::stats {

class StatisticsError : public BadInput {
 public:
  explicit StatisticsError(const std::string& what) : BadInput(what) {}
};

// The tests' first check: every value a finite number.
inline void require_finite(std::span<const double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) throw StatisticsError("a value is not a finite number");
  }
}

}  // namespace palprig::stats
