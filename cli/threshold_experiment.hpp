#pragma once
// `palprig experiment run` for threshold protocols (issue 13): staircases and QUEST on the rig.
// cli/experiment_command.cpp hands over when the protocol file says "task": "threshold".
#include <cstdint>
#include <optional>
#include <string>

namespace palprig::cli {

struct ThresholdRunRequest {
  std::string protocol, participant, db, rig, cal;
  bool resume = false, quiet = false;
  std::optional<std::uint64_t> seed;
  double speed = 0;                 // simulated participants: 0 = simulated time, else times real time
  double sim_noise_kPa = 0.8;       // simulated observer: per-finger noise sd
  double sim_criterion_kPa = 0.5;   // simulated observer: yes-no criterion
};

void run_threshold_experiment(const ThresholdRunRequest& request);

}  // namespace palprig::cli
