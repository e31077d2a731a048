// Stiffness maps as CSV (with and without a value scale).
#include <sstream>

#include "fuzz/fuzz_input.hpp"
#include "models/stiffness_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(palprig::fuzz::text(data, size));
  for (double scale : {0.0, 65535.0}) {
    std::istringstream in(text);
    palprig::fuzz::refused_or_read([&] { (void)palprig::parse_stiffness_csv(in, "fuzz.csv", 100, 100, scale); });
  }
  return 0;
}
