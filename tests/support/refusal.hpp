#pragma once
// What a reader refuses: the InputError's one line, or "accepted" when it took the input.
// Shared by the suites that check refusals (the calibration ones first).
#include <functional>
#include <string>

#include "core/input_error.hpp"

namespace palprig::test_support {

inline std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace palprig::test_support
