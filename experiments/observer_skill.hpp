#pragma once
// The simulated trainee who learns (a training curriculum's pilot): its skill is the probability
// that the simulated observer reports what it felt, rising with the cases practised,
// 1 - (1 - initial) exp(-rate n) (study/training.hpp: pilot_skill), n counting the cases of
// earlier sessions and those of this session before the case at hand. The default is the
// fully skilled observer (skill 1, as every study's sim:SEED), which draws no extra random
// number, so sessions without a pilot stay bit-identical.
#include "study/training.hpp"

namespace palprig {

struct ObserverSkill {
  CurriculumPilot pilot{1.0, 0.0};  // initial skill, learning rate per case
  int cases_practised = 0;          // before this session
  bool learns() const noexcept { return pilot.initial_skill < 1.0; }
  // The skill at the session's case `case_index` (0-based).
  double at(int case_index) const { return pilot_skill(pilot, cases_practised + case_index); }
};

}  // namespace palprig
