// Calibration files through their validator.
#include "formats/calibration_file.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] { palprig::load_calibration_file(path); });
  return 0;
}
