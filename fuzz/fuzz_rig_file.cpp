// Rig files through their validator (safety, plant, tablet, Modbus map, comedi sections).
#include "formats/rig_file.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] { palprig::load_rig_file(path); });
  return 0;
}
