#pragma once
// Typed lines from a terminal (or a pipe), read without ever blocking the session loop; shared
// by the terminal participants of every task. "q" or the end of input sets the stop request
// (SIGTERM's number): the session stops and stays resumable.
#include <atomic>
#include <optional>
#include <string>

namespace palprig {

class TerminalLines {
 public:
  TerminalLines(int input_fd, std::atomic<int>& stop_request) : input_fd_(input_fd), stop_request_(stop_request) {}

  // One complete line (without its newline or a trailing CR) if one has arrived.
  std::optional<std::string> next();

 private:
  int input_fd_;
  std::atomic<int>& stop_request_;
  std::string pending_;
  bool eof_ = false;
};

}  // namespace palprig
