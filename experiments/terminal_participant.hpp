#pragma once
// TerminalParticipant: a person at a text terminal. Prompts go to an output stream; answers are
// typed lines read from a file descriptor without ever blocking the session loop ("2", "12",
// "0" for no tumor) and, when the protocol asks for a confidence rating, one more line with the
// rating 1..levels (both re-asked on bad input); Enter goes on after a break; "q" or the end of input asks the session
// to stop (it stays resumable). Discrimination only: a person palpates a scene with the pen, which a terminal does not
// read.
#include <iosfwd>
#include <optional>
#include <string>

#include "experiments/participant.hpp"
#include "study/protocol.hpp"
#include "experiments/terminal_lines.hpp"

namespace palprig {

class TerminalParticipant final : public Participant {
 public:
  // `control` is asked to stop when the person quits (q) or the input ends.
  TerminalParticipant(const Protocol& protocol, std::ostream& prompts, RunControl& control, int input_fd = 0);

  bool ready(double t_s) override;
  void trial_started(const PlannedTrial& trial, const Condition& condition, double t_s) override;
  void feel(const FeltSample&) override {}
  std::optional<Response> answer(double t_s) override;
  bool answering() override { return pending_.has_value(); }  // the rating line is awaited

 private:
  const Protocol& protocol_;
  std::ostream& out_;
  TerminalLines lines_;
  bool prompted_ready_ = false;
  std::optional<Response> pending_;  // the finger answer, waiting for its confidence rating
  void ask_confidence();
};

}  // namespace palprig
