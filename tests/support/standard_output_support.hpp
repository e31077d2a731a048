#pragma once
// Running palprig with its standard output on a device that refuses writes (/dev/full) or on a
// pipe whose reader has gone, for the tests of cli/standard_output.hpp.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig::test_support {

struct EndedProcess {
  bool signalled = false;
  int code = -1;  // the exit status, or the signal's number when signalled
  std::string err;
};

// `palprig ARGS` (a shell word list) with standard output on /dev/full.
inline ProcessResult run_to_dev_full(const std::string& args) {
  TempDir dir;
  const auto err = dir.path() / "stderr";
  const std::string cmd = palprig_bin() + " " + args + " >/dev/full 2>" + err.string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  ProcessResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = read_file(err);
  return r;
}

// `palprig ARGS` with standard output on a pipe whose read end is already closed. With
// `parent_ignores_sigpipe` SIGPIPE is ignored in the child as some parents leave it (Python, a
// service manager): every write then fails with EPIPE instead of killing the process, so what
// palprig does about it is what is seen; without, SIGPIPE is at its default, as in a shell.
inline EndedProcess run_into_closed_pipe(const std::vector<std::string>& args, bool parent_ignores_sigpipe = true) {
  TempDir dir;
  const auto err = dir.path() / "stderr";
  int fds[2];
  if (::pipe(fds) != 0) return {};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGPIPE, parent_ignores_sigpipe ? SIG_IGN : SIG_DFL);
    ::close(fds[0]);
    ::dup2(fds[1], STDOUT_FILENO);
    ::close(fds[1]);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(e, STDERR_FILENO);
    const int in = ::open("/dev/null", O_RDONLY);
    ::dup2(in, STDIN_FILENO);
    std::vector<std::string> copy = args;
    std::string bin = palprig_bin();
    std::vector<char*> argv{bin.data()};
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(bin.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(fds[0]);
  ::close(fds[1]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EndedProcess r;
  r.signalled = WIFSIGNALED(status);
  r.code = r.signalled ? WTERMSIG(status) : WEXITSTATUS(status);
  r.err = read_file(err);
  return r;
}

}  // namespace palprig::test_support
