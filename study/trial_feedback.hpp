#pragma once
// What a participant is told about a trial after it is committed, when the protocol asks for
// feedback ("feedback": "practice" or "all"; default "none": the participant learns nothing
// about correctness, which would train them during the study). The terminal prints it and the
// window's participant screen shows it, both through the session listener
// (SessionListener::participant_feedback), so the words are the same everywhere.
#include <optional>
#include <string>

#include "study/protocol.hpp"
#include "study/trial_record.hpp"

namespace palprig {

// Nothing when the protocol gives no feedback for this trial. Discrimination: "Correct." or
// where the tumor was against the answer; localisation: the tumors found and missed, false
// marks; an unanswered trial: "No answer in time."
std::optional<std::string> trial_feedback(const Protocol& protocol, const TrialRecord& trial);

}  // namespace palprig
