// The CSV tables `palprig calibrate fit` reads: stress pairs (then the actuator line of each
// channel), force-window presses and sweep recordings, each from the same bytes.
#include "calibration/force_window.hpp"
#include "calibration/stress_fit.hpp"
#include "calibration/sweep_csv.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".csv");
  palprig::fuzz::refused_or_read([&] {
    const auto pairs = palprig::read_stress_pairs_csv(path);
    for (int channel = 1; channel <= 3; ++channel)
      palprig::fuzz::refused_or_read([&] { (void)palprig::fit_actuator_stress(pairs, channel, path.string()); });
  });
  palprig::fuzz::refused_or_read([&] { (void)palprig::force_window_from_presses(path); });
  palprig::fuzz::refused_or_read([&] { (void)palprig::read_sweep_csv(path); });
  return 0;
}
