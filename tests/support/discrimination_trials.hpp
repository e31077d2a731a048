#pragma once
// A discrimination trial as a session would commit it, made from a protocol's planned trial with
// no rig: the truth and stimulus of its combination, answered either exactly (the truth) or with
// every finger ("answer_all", wrong unless all three carry a tumor). Study data only, so the
// analyst-only build's suites use it too.
#include "study/protocol.hpp"
#include "study/scoring.hpp"
#include "study/session_plan.hpp"
#include "study/trial_record.hpp"

namespace palprig::testing {

inline TrialRecord discrimination_trial(const Protocol& p, const PlannedTrial& planned, bool answer_all) {
  TrialRecord r;
  r.planned = planned;
  r.condition = p.conditions[static_cast<std::size_t>(planned.condition)].name;
  r.mode = p.conditions[static_cast<std::size_t>(planned.condition)].mode;
  const auto& c = p.combinations[static_cast<std::size_t>(planned.combination)];
  r.combination_label = c.label;
  r.stimulus_kPa = c.pressure_kPa;
  r.truth = c.tumor;
  r.answered = true;
  r.answer = answer_all ? FingerFlags{true, true, true} : c.tumor;
  r.finger_outcomes = score_discrimination(r.truth, r.answer);
  r.onset_s = 10.0 * planned.position;
  r.response_time_s = 4.5;
  r.felt_kPa = c.pressure_kPa;
  return r;
}

}  // namespace palprig::testing
