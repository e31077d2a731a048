// The statistics commands' CSV tables: parsed, then every column read as numbers and labels.
#include "fuzz/fuzz_input.hpp"
#include "statistics/csv_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  palprig::fuzz::refused_or_read([&] {
    const palprig::CsvTable t = palprig::CsvTable::parse(palprig::fuzz::text(data, size), "fuzz.csv");
    for (std::size_t c = 0; c < t.header().size(); ++c) {
      palprig::fuzz::refused_or_read([&] { (void)t.numbers(t.header()[c]); });
      for (std::size_t r = 0; r < t.rows(); ++r) palprig::fuzz::refused_or_read([&] { (void)t.label(r, c); });
    }
  });
  return 0;
}
