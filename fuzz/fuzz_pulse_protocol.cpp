// Pulse-localisation protocols through their validator. The input is read as the command reads
// it, but its scene paths resolve against the shipped data/protocols folder (the fuzz input
// lives in /dev/shm), so mutations reach the scene loading and artery checks, not only
// "file not found".
#include "formats/json_file.hpp"
#include "fuzz/fuzz_input.hpp"
#include "study/pulse_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] {
    palprig::parse_pulse_protocol(palprig::read_json_file(path), path.string(),
                                  std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "protocols");
  });
  return 0;
}
