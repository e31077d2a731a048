// Tracking files through their validator: tools, fingers, tips, the registration.
#include "formats/tracking_file.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] {
    const palprig::TrackingConfig t = palprig::load_tracking_file(path);
    (void)palprig::tracking_text(t);
  });
  return 0;
}
