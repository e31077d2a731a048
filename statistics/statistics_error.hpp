#pragma once
// StatisticsError: a test cannot be computed from the data it was given (too few values, a
// constant sample, an empty group). It is a BadInput (core/error.hpp): the command line turns it
// into one line naming the file and the column, exit code 2.
#include <string>

#include "core/error.hpp"

namespace palprig::stats {

class StatisticsError : public BadInput {
 public:
  explicit StatisticsError(const std::string& what) : BadInput(what) {}
};

}  // namespace palprig::stats
