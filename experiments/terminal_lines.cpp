#include "experiments/terminal_lines.hpp"

#include <poll.h>
#include <unistd.h>

namespace palprig {

std::optional<std::string> TerminalLines::next() {
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
    if (eof_) control_.request_stop();
    return std::nullopt;
  }
  std::string line = pending_.substr(0, newline);
  pending_.erase(0, newline + 1);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line == "q") {
    control_.request_stop();
    return std::nullopt;
  }
  return line;
}

}  // namespace palprig
