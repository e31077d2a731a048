#include "study/localisation_case.hpp"

#include "formats/function_scene_file.hpp"
#include "formats/json_file.hpp"
#include "formats/scene_file.hpp"

namespace palprig {

SceneFile generated_case_scene(std::uint64_t seed, CaseDifficulty difficulty) {
  const nlohmann::json doc = generated_case_json(generate_case(seed, difficulty));
  const std::string source = "generated case (seed " + std::to_string(seed) + ", " + to_string(difficulty) + ")";
  const JsonObject root(doc, source, "");
  root.require_version(kSceneFileVersion);
  SceneFile out;
  out.source = source;
  out.name = root.string_or("name", "generated");
  (void)root.choice_or("kind", "function", {"function"});
  (void)root.string_or("description", "");
  load_function_scene(root, std::filesystem::path("."), out);
  return out;
}

LocalisationCase generated_localisation_case(std::uint64_t seed, CaseDifficulty difficulty) {
  const SceneFile scene = generated_case_scene(seed, difficulty);
  LocalisationCase c;
  c.name = scene.name;
  c.seed = seed;
  c.difficulty = difficulty;
  c.tumors = scene.tumors;
  return c;
}

LocalisationCase file_localisation_case(const std::filesystem::path& scene_file) {
  const SceneFile scene = load_scene_file(scene_file);
  LocalisationCase c;
  c.name = scene.name.empty() ? scene_file.stem().string() : scene.name;
  c.scene_file = scene_file;
  c.tumors = scene.tumors;
  return c;
}

std::uint64_t generated_case_seed(std::uint64_t session_seed, int position) noexcept {
  // A position's own stream of the session seed (splitmix64's finaliser): neighbouring positions
  // and neighbouring sessions give unrelated cases.
  std::uint64_t z = session_seed + 0x9E3779B97F4A7C15ULL * (static_cast<std::uint64_t>(position) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return (z ^ (z >> 31)) % 1000000000ULL;  // a seed a person can type again (`scene generate --seed`)
}

LocalisationCase trial_case(const Protocol& protocol, const PlannedTrial& trial, std::uint64_t session_seed) {
  const LocalisationTask& task = protocol.localisation;
  if (task.generate)
    return generated_localisation_case(generated_case_seed(session_seed, trial.position), *task.generate);
  const std::size_t index = trial.combination >= 0 ? static_cast<std::size_t>(trial.combination) : 0;
  return task.cases.at(index);
}

SceneFile case_scene(const LocalisationCase& c) {
  if (c.seed && c.difficulty) return generated_case_scene(*c.seed, *c.difficulty);
  return load_scene_file(c.scene_file);
}

std::string generated_case_key(CaseDifficulty difficulty, std::uint64_t seed) {
  return std::string("generated:") + to_string(difficulty) + ":" + std::to_string(seed);
}

std::string case_key(const LocalisationCase& c) {
  if (c.seed && c.difficulty) return generated_case_key(*c.difficulty, *c.seed);
  return "scene:" + c.name;
}

}  // namespace palprig
