#include "experiments/terminal_participant.hpp"

#include <poll.h>
#include <unistd.h>

#include <csignal>
#include <ostream>

namespace palprig {

TerminalParticipant::TerminalParticipant(const Protocol& protocol, std::ostream& prompts,
                                         std::atomic<int>& stop_request, int input_fd)
    : protocol_(protocol), out_(prompts), stop_request_(stop_request), input_fd_(input_fd) {}

bool TerminalParticipant::ready(double) {
  if (!prompted_ready_) {
    out_ << "Ready? Press Enter to start (q + Enter stops; the session can be resumed).\n" << std::flush;
    prompted_ready_ = true;
  }
  const auto line = next_line();
  if (!line) return false;
  prompted_ready_ = false;
  return true;
}

void TerminalParticipant::trial_started(const PlannedTrial& trial, const Condition& condition, double) {
  out_ << "\nTrial " << trial.position + 1 << (trial.practice ? " (practice)" : "") << ", " << condition.name
       << (condition.mode == PresentationMode::sequential ? ": the fingers are presented one after another"
                                                          : ": all fingers at once")
       << ".\n  Which fingers feel a tumor? Type their numbers (1 = " << protocol_.finger_names[0]
       << ", 2 = " << protocol_.finger_names[1] << ", 3 = " << protocol_.finger_names[2]
       << "), or 0 for none, then Enter.\n"
       << std::flush;
}

std::optional<Response> TerminalParticipant::answer(double) {
  const auto line = next_line();
  if (!line) return std::nullopt;
  Response r;
  bool ok = !line->empty();
  bool none = false;
  for (char c : *line) {
    if (c == '0' || c == 'n') none = true;
    else if (c >= '1' && c <= '0' + kFingerCount) r.tumor_under[static_cast<std::size_t>(c - '1')] = true;
    else if (c != ' ' && c != ',') ok = false;
  }
  const bool any = r.tumor_under[0] || r.tumor_under[1] || r.tumor_under[2];
  if (!ok || (none && any)) {
    out_ << "  Please type finger numbers 1-" << kFingerCount << " (e.g. 2 or 23), or 0 for no tumor.\n" << std::flush;
    return std::nullopt;
  }
  return r;
}

std::optional<std::string> TerminalParticipant::next_line() {
  pollfd p{input_fd_, POLLIN, 0};
  while (!eof_ && ::poll(&p, 1, 0) > 0 && (p.revents & (POLLIN | POLLHUP))) {
    char buf[256];
    const ssize_t n = ::read(input_fd_, buf, sizeof buf);
    if (n <= 0) {
      eof_ = true;
      break;
    }
    pending_.append(buf, static_cast<std::size_t>(n));
    if (pending_.find('\n') != std::string::npos) break;
  }
  const auto newline = pending_.find('\n');
  if (newline == std::string::npos) {
    if (eof_) stop_request_.store(SIGTERM);
    return std::nullopt;
  }
  std::string line = pending_.substr(0, newline);
  pending_.erase(0, newline + 1);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line == "q") {
    stop_request_.store(SIGTERM);
    return std::nullopt;
  }
  return line;
}

}  // namespace palprig
