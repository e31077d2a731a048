#pragma once
// A person at a text terminal in a threshold session: "1"/"2" for the stronger interval (2AFC),
// "y"/"n" for "was the second interval stronger?" (yes-no); lines read through TerminalLines,
// so the session loop never blocks and "q" or the end of input stops (resumable).
#include <iosfwd>
#include <optional>

#include "experiments/terminal_lines.hpp"
#include "experiments/threshold_session.hpp"

namespace palprig {

class TerminalThresholdParticipant final : public ThresholdParticipant {
 public:
  TerminalThresholdParticipant(ThresholdMethod method, std::ostream& prompts, RunControl& control, int input_fd = 0)
      : method_(method), out_(prompts), lines_(input_fd, control) {}

  bool ready(double t_s) override;
  void trial_started(const ThresholdTrialInfo& trial, double t_s) override;
  void interval_started(int interval, double t_s) override;
  void feel(int, const FeltSample&) override {}
  std::optional<int> answer(double t_s) override;

 private:
  ThresholdMethod method_;
  std::ostream& out_;
  TerminalLines lines_;
  bool prompted_ = false, asked_ = false;
};

}  // namespace palprig
