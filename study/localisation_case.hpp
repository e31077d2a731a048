#pragma once
// Which case each localisation trial palpates, and its scene: a protocol's one scene, an item of
// its listed cases (PlannedTrial::combination), or a new generated case per trial seeded by the
// session seed and the trial's position (so a resumed session, an export or a window showing the
// trial makes the same case again). Pure: the same inputs give the same case.
#include <cstdint>
#include <string>

#include "formats/scene_description.hpp"
#include "models/case_generator.hpp"
#include "study/protocol.hpp"
#include "study/session_plan.hpp"

namespace palprig {

// A generated rehearsal case as the scene a trial palpates (models/case_generator through the
// function scene loader, as `palprig scene generate` writes it).
SceneFile generated_case_scene(std::uint64_t seed, CaseDifficulty difficulty);
// Its name and ground truth (the scene's tumor outlines).
LocalisationCase generated_localisation_case(std::uint64_t seed, CaseDifficulty difficulty);
// A scene file's case: its name and tumor outlines (none: a normal case). Throws InputError.
LocalisationCase file_localisation_case(const std::filesystem::path& scene_file);

// The seed of the case a "generate" protocol presents at `position` of a session.
std::uint64_t generated_case_seed(std::uint64_t session_seed, int position) noexcept;

// The case of one planned trial.
LocalisationCase trial_case(const Protocol& protocol, const PlannedTrial& trial, std::uint64_t session_seed);
// The scene of a case: its file loaded, or the generated case made again.
SceneFile case_scene(const LocalisationCase& c);

// What identifies a case across sessions ("generated:medium:42"; "scene:<name>" for a file):
// a trainee is never given the same generated case twice.
std::string case_key(const LocalisationCase& c);
std::string generated_case_key(CaseDifficulty difficulty, std::uint64_t seed);

}  // namespace palprig
