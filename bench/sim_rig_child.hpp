// What the two end-to-end benchmarks (bench_pen_to_modbus, bench_pose_to_modbus) share: the
// `palprig sim-rig` they measure against, started as a child at SCHED_FIFO 50 (chrt) with its
// stdout on a pipe (it prints the port it listens on), and the percentile of their tables.
// Header-only: each benchmark is one program of one file (bench/CMakeLists.txt).
#pragma once

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace palprig::bench {

// The running child; stopped (SIGTERM, reaped) when it goes out of scope, early returns included.
struct SimRigChild {
  pid_t pid = -1;
  FILE* out = nullptr;  // the child's stdout

  SimRigChild() = default;
  SimRigChild(SimRigChild&& other) noexcept : pid(other.pid), out(other.out) {
    other.pid = -1;
    other.out = nullptr;
  }
  SimRigChild(const SimRigChild&) = delete;
  SimRigChild& operator=(const SimRigChild&) = delete;
  SimRigChild& operator=(SimRigChild&&) = delete;
  ~SimRigChild() { stop(); }

  // The port sim-rig says it listens on ("listening on 127.0.0.1:PORT"), or 0 when it ended first.
  int wait_for_port() {
    char line[512];
    while (out && std::fgets(line, sizeof line, out)) {
      const std::string l = line;
      const auto at = l.find("listening on 127.0.0.1:");
      if (at != std::string::npos) return std::atoi(l.c_str() + at + 23);
    }
    return 0;
  }

  // SIGTERM, reaped, its pipe closed.
  void stop() {
    if (pid > 0) {
      kill(pid, SIGTERM);
      waitpid(pid, nullptr, 0);
      pid = -1;
    }
    if (out) {
      std::fclose(out);
      out = nullptr;
    }
  }
};

// `chrt -f 50 palprig sim-rig --rig RIG --listen 127.0.0.1:0 --write-log WRITE_LOG EXTRA...`
// (PALPRIG_BIN: the benchmark target's compile definition).
inline SimRigChild spawn_sim_rig(const std::string& rig, const std::string& write_log,
                                 const std::vector<std::string>& extra = {}) {
  int fds[2];
  if (pipe(fds) != 0) throw Error("pipe");
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
  posix_spawn_file_actions_addclose(&fa, fds[0]);
  std::vector<std::string> args = {"chrt", "-f",       "50",          PALPRIG_BIN,   "sim-rig", "--rig",
                                   rig,    "--listen", "127.0.0.1:0", "--write-log", write_log};
  args.insert(args.end(), extra.begin(), extra.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  SimRigChild c;
  const int spawned = posix_spawnp(&c.pid, "chrt", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[1]);
  if (spawned != 0) {
    close(fds[0]);
    throw Error("spawn sim-rig");
  }
  c.out = fdopen(fds[0], "r");
  return c;
}

// The q-quantile of v by rank (0 for none): q 0.5 the median, 1.0 the largest.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

}  // namespace palprig::bench
