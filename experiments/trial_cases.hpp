#pragma once
// TrialCases: the CaseSource of a localisation session (experiments/trial_runner.hpp): each
// trial's case (study/localisation_case.hpp) and its scene, made once per trial (a file's scene
// is kept while consecutive trials present it; a generated case is made from its seed).
#include <cstdint>
#include <string>

#include "experiments/trial_runner.hpp"
#include "formats/scene_description.hpp"

namespace palprig {

class TrialCases final : public CaseSource {
 public:
  TrialCases(const Protocol& protocol, std::uint64_t session_seed) : protocol_(protocol), seed_(session_seed) {}

  const LocalisationCase& case_of(const PlannedTrial& trial) override;
  const Scene& scene_of(const PlannedTrial& trial) override;

 private:
  void load(const PlannedTrial& trial);

  const Protocol& protocol_;
  std::uint64_t seed_;
  int position_ = -1;
  std::string key_;  // case_key of the scene held
  LocalisationCase case_;
  SceneFile scene_;
};

}  // namespace palprig
