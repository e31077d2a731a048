#include "cli/standard_output.hpp"

#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <iostream>
#include <streambuf>
#include <vector>

namespace palprig::cli {

namespace {

// std::cout's buffer: writes to file descriptor 1 with write(2), remembers the first failure's
// errno and drops everything after it (a reader that went away reads nothing more).
class CheckedOutputBuffer final : public std::streambuf {
 public:
  CheckedOutputBuffer() : buffer_(std::size_t{64} * 1024), line_buffered_(::isatty(STDOUT_FILENO) == 1) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }

  int error() const noexcept { return error_; }

  // Writes what is buffered; false once any write failed.
  bool drain() {
    const char* data = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0 && error_ == 0) {
      const ssize_t n = ::write(STDOUT_FILENO, data, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
      } else if (n == 0) {
        error_ = EIO;
      } else {
        data += n;
        left -= static_cast<std::size_t>(n);
      }
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return error_ == 0;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
      if (line_buffered_ && traits_type::to_char_type(c) == '\n' && !drain()) return traits_type::eof();
    }
    return traits_type::not_eof(c);
  }

  std::streamsize xsputn(const char* s, std::streamsize count) override {
    std::streamsize done = 0;
    while (done < count) {
      if (pptr() == epptr() && !drain()) return done;
      const std::streamsize room = epptr() - pptr();
      const std::streamsize part = std::min(room, count - done);
      std::memcpy(pptr(), s + done, static_cast<std::size_t>(part));
      pbump(static_cast<int>(part));
      done += part;
    }
    if (line_buffered_ && std::memchr(s, '\n', static_cast<std::size_t>(count)) != nullptr) drain();
    return done;
  }

  int sync() override { return drain() ? 0 : -1; }

 private:
  std::vector<char> buffer_;
  bool line_buffered_;
  int error_ = 0;
};

CheckedOutputBuffer* checked_buffer = nullptr;

}  // namespace

void check_standard_output() {
  if (checked_buffer) return;
  // A closed pipe is seen as EPIPE at the write, handled at the end (see the header).
  std::signal(SIGPIPE, SIG_IGN);
  // Never destroyed: std::cout outlives every static of the program (its last flush runs in
  // std::ios_base::Init's destructor, at the end of exit(), after the function-local statics
  // are gone; a shared library such as libOpenIGTLink holds such an Init too). A buffer
  // destroyed before that flush is a use after free: every palprig process crashed at exit under
  // AddressSanitizer. The pointer above keeps it reachable, so LeakSanitizer does not count it.
  checked_buffer = new CheckedOutputBuffer;
  std::cout.rdbuf(checked_buffer);
}

int finish_standard_output(int exit_code) {
  if (!checked_buffer) return exit_code;
  std::cout.flush();
  checked_buffer->drain();
  const int error = checked_buffer->error();
  if (error == 0) return exit_code;
  if (error == EPIPE) {
    if (exit_code != 0) return exit_code;
    // The reader went away: end as a Unix tool ends there, by the signal, quietly.
    std::cerr.flush();
    std::signal(SIGPIPE, SIG_DFL);
    std::raise(SIGPIPE);
    return 141;  // not reached: SIGPIPE's default action ends the process
  }
  std::cerr << "palprig: standard output: cannot write: " << std::strerror(error) << "\n";
  return exit_code != 0 ? exit_code : 1;
}

}  // namespace palprig::cli
