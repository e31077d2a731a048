#include "models/fe_bodies.hpp"

namespace palprig {

const char* to_string(BlockSides s) noexcept { return s == BlockSides::rollers ? "rollers" : "free"; }

}  // namespace palprig
