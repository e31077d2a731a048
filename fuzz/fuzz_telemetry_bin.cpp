// Binary telemetry (`palprig telemetry to-csv`): any record bytes, any length.
#include "controller/telemetry_writer.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".bin");
  palprig::fuzz::refused_or_read([&] { palprig::convert_telemetry_to_csv(path, "/dev/null"); });
  return 0;
}
