// The finite-element model's result files (formats/fe_result_files.hpp): a stress model file
// (calibrate fit --stress-model) or a table (a function scene's fe_stress_table), by its kind,
// then one lookup across the whole table's range.
#include "formats/fe_result_files.hpp"
#include "formats/json_file.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] {
    const auto doc = palprig::read_json_file(path);
    if (palprig::fe_result_kind(doc) == "fe_stress_table") {
      const auto t = palprig::parse_fe_table(doc, path.string());
      const auto& ax = t.table->axes();
      (void)t.table->rise_kPa(ax.indentation_mm.back() * 0.7, ax.cover_mm.front(), ax.diameter_mm.back() * 2,
                              ax.contrast.front() * 0.5, ax.offset_mm.back() * 0.5);
    } else {
      (void)palprig::parse_stress_model(doc, path.string());
    }
  });
  return 0;
}
