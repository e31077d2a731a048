#include "experiments/terminal_participant.hpp"

#include <ostream>

namespace palprig {

TerminalParticipant::TerminalParticipant(const Protocol& protocol, std::ostream& prompts, RunControl& control,
                                         int input_fd)
    : protocol_(protocol), out_(prompts), lines_(input_fd, control) {}

bool TerminalParticipant::ready(double) {
  if (!prompted_ready_) {
    out_ << "Ready? Press Enter to start (q + Enter stops; the session can be resumed).\n" << std::flush;
    prompted_ready_ = true;
  }
  const auto line = lines_.next();
  if (!line) return false;
  prompted_ready_ = false;
  return true;
}

void TerminalParticipant::trial_started(const PlannedTrial& trial, const Condition& condition, double) {
  pending_.reset();  // a trial dropped by a pause is presented again from its start
  out_ << "\nTrial " << trial.position + 1 << (trial.practice ? " (practice)" : "") << ", " << condition.name
       << (condition.mode == PresentationMode::sequential ? ": the fingers are presented one after another"
                                                          : ": all fingers at once")
       << ".\n  Which fingers feel a tumor? Type their numbers (1 = " << protocol_.finger_names[0]
       << ", 2 = " << protocol_.finger_names[1] << ", 3 = " << protocol_.finger_names[2]
       << "), or 0 for none, then Enter.\n"
       << std::flush;
}

void TerminalParticipant::ask_confidence() {
  const ConfidenceScale& scale = protocol_.confidence;
  out_ << "  How confident are you? Type 1-" << scale.levels;
  if (!scale.labels.empty()) {
    out_ << " (";
    for (std::size_t i = 0; i < scale.labels.size(); ++i) out_ << (i ? ", " : "") << i + 1 << " = " << scale.labels[i];
    out_ << ")";
  }
  out_ << ", then Enter.\n" << std::flush;
}

std::optional<Response> TerminalParticipant::answer(double t_s) {
  const auto line = lines_.next();
  if (!line) return std::nullopt;
  if (pending_) {
    // The rating line: exactly one digit 1..levels (spaces around it allowed).
    const auto first = line->find_first_not_of(' ');
    const auto last = line->find_last_not_of(' ');
    const bool one_digit =
        first != std::string::npos && first == last && (*line)[first] >= '1' && (*line)[first] <= '9';
    const int rating = one_digit ? (*line)[first] - '0' : 0;
    if (!protocol_.confidence.valid(rating)) {
      out_ << "  Please type one number from 1 to " << protocol_.confidence.levels << ".\n" << std::flush;
      return std::nullopt;
    }
    Response r = *pending_;
    r.confidence = rating;
    pending_.reset();
    return r;
  }
  Response r;
  bool ok = !line->empty();
  bool none = false;
  for (char c : *line) {
    if (c == '0' || c == 'n')
      none = true;
    else if (c >= '1' && c <= '0' + kFingerCount)
      r.tumor_under[static_cast<std::size_t>(c - '1')] = true;
    else if (c != ' ' && c != ',')
      ok = false;
  }
  const bool any = r.tumor_under[0] || r.tumor_under[1] || r.tumor_under[2];
  if (!ok || (none && any)) {
    out_ << "  Please type finger numbers 1-" << kFingerCount << " (e.g. 2 or 23), or 0 for no tumor.\n" << std::flush;
    return std::nullopt;
  }
  if (protocol_.confidence.asked()) {
    r.given_at_s = t_s;  // the response time ends with the finger answer, not with the rating
    pending_ = r;
    ask_confidence();
    return std::nullopt;
  }
  return r;
}

}  // namespace palprig
