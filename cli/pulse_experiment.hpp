#pragma once
// `palprig experiment run` for pulse-localisation protocols (paper 000).
// cli/experiment_command.cpp hands over when the protocol file says "task": "pulse"; the session
// is sessions/pulse_study's run_pulse_study; this file prints.
#include "sessions/study_session.hpp"

namespace palprig::cli {

void run_pulse_experiment(const StudySessionRequest& request, bool quiet);

}  // namespace palprig::cli
