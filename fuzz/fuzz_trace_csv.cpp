// Recorded pen traces (CSV t_s,x_mm,y_mm,force_N), then replayed through TraceInput.
#include "fuzz/fuzz_input.hpp"
#include "inputs/input_source.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".csv");
  palprig::fuzz::refused_or_read([&] {
    palprig::TraceInput trace(palprig::load_trace_csv(path), "fuzz");
    for (double t = -0.01; t < trace.duration_s() + 0.02; t += trace.duration_s() / 16 + 1e-3) (void)trace.latest(t);
  });
  return 0;
}
