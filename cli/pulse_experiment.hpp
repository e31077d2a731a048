#pragma once
// `palprig experiment run` for pulse-localisation protocols (issue 13, paper 000).
// cli/experiment_command.cpp hands over when the protocol file says "task": "pulse".
#include <cstdint>
#include <optional>
#include <string>

namespace palprig::cli {

struct PulseRunRequest {
  std::string protocol, participant, db, rig, cal;
  bool resume = false, quiet = false;
  std::optional<std::uint64_t> seed;
  double speed = 0;
};

void run_pulse_experiment(const PulseRunRequest& request);

}  // namespace palprig::cli
