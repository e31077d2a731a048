#include "experiments/trial_cases.hpp"

#include "study/localisation_case.hpp"

namespace palprig {

void TrialCases::load(const PlannedTrial& trial) {
  if (trial.position == position_ && scene_.scene) return;
  position_ = trial.position;
  if (protocol_.localisation.generate) {
    // Made once: the case's ground truth is its scene's.
    const std::uint64_t seed = generated_case_seed(seed_, trial.position);
    scene_ = generated_case_scene(seed, *protocol_.localisation.generate);
    case_ = LocalisationCase{scene_.name, {}, seed, protocol_.localisation.generate, scene_.tumors};
    key_ = case_key(case_);
    return;
  }
  case_ = trial_case(protocol_, trial, seed_);
  const std::string key = case_key(case_);
  if (key != key_ || !scene_.scene) {
    scene_ = case_scene(case_);
    key_ = key;
  }
}

const LocalisationCase& TrialCases::case_of(const PlannedTrial& trial) {
  load(trial);
  return case_;
}

const Scene& TrialCases::scene_of(const PlannedTrial& trial) {
  load(trial);
  return *scene_.scene;
}

}  // namespace palprig
