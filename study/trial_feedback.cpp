#include "study/trial_feedback.hpp"

namespace palprig {

namespace {

// "index and middle", "ring", "none".
std::string finger_list(const Protocol& protocol, const FingerFlags& fingers) {
  std::string out;
  int count = 0;
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    if (!fingers[f]) continue;
    if (count++ > 0) out += " and ";
    out += protocol.finger_names[f];
  }
  return count == 0 ? "no finger" : out;
}

std::string discrimination_feedback(const Protocol& protocol, const TrialRecord& trial) {
  if (trial.answer == trial.truth) return "Correct.";
  const bool any_tumor = trial.truth[0] || trial.truth[1] || trial.truth[2];
  return "Not quite: " +
         (any_tumor ? "the tumor was under " + finger_list(protocol, trial.truth) : std::string("there was no tumor")) +
         "; you answered " + finger_list(protocol, trial.answer) + ".";
}

std::string localisation_feedback(const TrialRecord& trial) {
  if (trial.case_tumors == 0 && !trial.case_name.empty()) {
    // A normal case: "nothing there" is the right answer.
    if (trial.localisation.false_marks == 0) return "Correct: there was no tumor.";
    return "There was no tumor; marks on no tumor: " + std::to_string(trial.localisation.false_marks) + ".";
  }
  std::string found, missed;
  for (const TumorScore& t : trial.localisation.tumors) {
    std::string& list = t.hit ? found : missed;
    list += (list.empty() ? "" : ", ") + t.tumor;
  }
  std::string out = "Found: " + (found.empty() ? std::string("none") : found) + ".";
  if (!missed.empty()) out += " Missed: " + missed + ".";
  if (trial.localisation.false_marks > 0)
    out += " Marks on no tumor: " + std::to_string(trial.localisation.false_marks) + ".";
  return out;
}

}  // namespace

std::optional<std::string> trial_feedback(const Protocol& protocol, const TrialRecord& trial) {
  switch (protocol.feedback) {
    case Feedback::none: return std::nullopt;
    case Feedback::practice:
      if (!trial.planned.practice) return std::nullopt;
      break;
    case Feedback::all: break;
  }
  if (!trial.answered) return "No answer in time.";
  return protocol.task == TaskKind::discrimination ? discrimination_feedback(protocol, trial)
                                                   : localisation_feedback(trial);
}

}  // namespace palprig
