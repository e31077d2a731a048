#pragma once
// Generated pulse cases (protocol conditions with "generate"): a rehearsal case of
// models/case_generator with an artery crossing it. Pure: the same seed gives the same scene.
#include <cstdint>

#include "formats/scene_file.hpp"
#include "models/case_generator.hpp"

namespace palprig {

// A generated rehearsal case with one artery crossing the block from its cranial to its caudal
// edge, bending at a random point; deeper and fainter with difficulty (easy 6 mm, medium 10 mm,
// hard 14 mm deep). Same seed, same scene.
SceneFile generated_pulse_scene(std::uint64_t seed, CaseDifficulty difficulty);

}  // namespace palprig
