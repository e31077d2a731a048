#include "experiments/terminal_threshold_participant.hpp"

#include <ostream>

namespace palprig {

bool TerminalThresholdParticipant::ready(double) {
  if (!prompted_) {
    out_ << "Ready? Press Enter to start (q + Enter stops; the session can be resumed).\n" << std::flush;
    prompted_ = true;
  }
  return lines_.next().has_value();
}

void TerminalThresholdParticipant::trial_started(const ThresholdTrialInfo& trial, double) {
  out_ << "\nTrial " << trial.position + 1 << " ("
       << (trial.spec->fingers == FingerSet::one ? "one finger" : "three fingers") << ")\n"
       << std::flush;
}

void TerminalThresholdParticipant::interval_started(int interval, double) {
  out_ << "  interval " << interval + 1 << "\n" << std::flush;
}

std::optional<int> TerminalThresholdParticipant::answer(double) {
  const bool two_afc = method_ == ThresholdMethod::two_afc;
  if (!asked_) {
    out_ << (two_afc ? "  Which interval was stronger? Type 1 or 2, then Enter.\n"
                     : "  Was the second interval stronger? Type y or n, then Enter.\n")
         << std::flush;
    asked_ = true;
  }
  const auto line = lines_.next();
  if (!line) return std::nullopt;
  if (two_afc && (*line == "1" || *line == "2")) {
    asked_ = false;
    return *line == "1" ? 0 : 1;
  }
  if (!two_afc && (*line == "y" || *line == "n")) {
    asked_ = false;
    return *line == "y" ? 1 : 0;
  }
  out_ << (two_afc ? "  Please type 1 or 2.\n" : "  Please type y or n.\n") << std::flush;
  return std::nullopt;
}

}  // namespace palprig
