#pragma once
// Typed lines from a terminal (or a pipe), read without ever blocking the session loop; shared
// by the terminal participants of every task. "q" or the end of input asks the run to stop
// (RunControl::request_stop): the session stops and stays resumable.
#include <optional>
#include <string>

#include "runtime/run_control.hpp"

namespace palprig {

class TerminalLines {
 public:
  TerminalLines(int input_fd, RunControl& control) : input_fd_(input_fd), control_(control) {}

  // One complete line (without its newline or a trailing CR) if one has arrived.
  std::optional<std::string> next();

 private:
  int input_fd_;
  RunControl& control_;
  std::string pending_;
  bool eof_ = false;
};

}  // namespace palprig
