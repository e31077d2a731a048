#pragma once
// Runs a command line through /bin/sh and collects its exit code, stdout and stderr (via
// temporary files), for tests that drive the real palprig program.
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "tests/support/temp_dir.hpp"

namespace palprig::test_support {

struct ProcessResult {
  int exit_code = -1;
  std::string out, err;
};

inline ProcessResult run_process(const std::string& command_line) {
  TempDir dir;
  const auto out = dir.path() / "stdout", err = dir.path() / "stderr";
  const std::string cmd = command_line + " >" + out.string() + " 2>" + err.string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  ProcessResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

inline std::string palprig_bin() { return PALPRIG_BIN; }
inline std::string source_dir() { return PALPRIG_SOURCE_DIR; }

}  // namespace palprig::test_support
