// Pulse waveform tables (t_s,value over one beat) that function scenes name.
#include "formats/function_scene_file.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".csv");
  palprig::fuzz::refused_or_read([&] { (void)palprig::load_waveform_csv(path); });
  return 0;
}
