// Stiffness maps as PGM (binary P5 8/16-bit, ASCII P2).
#include <sstream>

#include "fuzz/fuzz_input.hpp"
#include "models/stiffness_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in{std::string(palprig::fuzz::text(data, size))};
  palprig::fuzz::refused_or_read([&] {
    const palprig::StiffnessMap m = palprig::parse_stiffness_pgm(in, "fuzz.pgm", 100, 100);
    (void)m.sample_bilinear(50, 50);
  });
  return 0;
}
