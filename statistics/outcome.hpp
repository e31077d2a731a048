#pragma once
// The four outcomes of a yes/no judgement against the truth, which the diagnostic measures
// count. Experiments' scoring produces them.
#include <cstdint>

namespace palprig {

enum class Outcome : std::uint8_t { tp, fn, tn, fp };

}  // namespace palprig
