// Tracker pose recordings (CSV t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw) that igtl-replay serves.
#include "fuzz/fuzz_input.hpp"
#include "inputs/pose_recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".csv");
  palprig::fuzz::refused_or_read([&] { (void)palprig::recorded_tools(palprig::load_pose_recording(path)); });
  return 0;
}
