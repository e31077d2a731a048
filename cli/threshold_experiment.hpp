#pragma once
// `palprig experiment run` for threshold protocols: staircases and QUEST on the rig.
// cli/experiment_command.cpp hands over when the protocol file says "task": "threshold"; the
// session is sessions/threshold_study's run_threshold_study; this file prints.
#include "sessions/threshold_study.hpp"

namespace palprig::cli {

void run_threshold_experiment(const ThresholdStudyRequest& request, bool quiet);

}  // namespace palprig::cli
