// Threshold (staircase and QUEST) protocols through their validator.
#include "fuzz/fuzz_input.hpp"
#include "study/threshold_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] { palprig::load_threshold_protocol(path); });
  return 0;
}
