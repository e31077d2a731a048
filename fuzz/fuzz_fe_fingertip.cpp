// Finite-element fingertip files (formats/fe_body_files.hpp) through their reader: every field, every
// material law and the geometric checks (a shape that cannot be meshed is a refusal).
#include "formats/fe_body_files.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] { (void)palprig::load_fingertip_file(path); });
  return 0;
}
