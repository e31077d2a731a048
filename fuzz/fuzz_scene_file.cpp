// Scene files through their validator: map scenes and function scenes (shapes, arteries).
// The map or waveform a scene names is looked up beside the input file; what the fuzzer can
// reach there is only the other fuzz inputs.
#include "formats/scene_file.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = palprig::fuzz::input_file(palprig::fuzz::text(data, size), ".json");
  palprig::fuzz::refused_or_read([&] {
    const palprig::SceneFile scene = palprig::load_scene_file(path);
    (void)scene.scene->sample({50, 50}, 2.0, 0.0);  // a loaded scene must also be sampled safely
  });
  return 0;
}
