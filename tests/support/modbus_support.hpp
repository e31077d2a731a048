#pragma once
// Helpers for the Modbus tests: real `palprig sim-rig` processes (started, read, killed, stopped
// and continued with real signals), rig files written with the port a simulator got, and the
// telemetry CSV and simulator write log read back.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace palprig::test_support {

// A child process with its stdout on a pipe (stderr to a file), killed on destruction.
class WatchedProcess {
 public:
  WatchedProcess(const std::vector<std::string>& argv, const std::string& stderr_path) {
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe failed");
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      dup2(out[1], 1);
      const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (err >= 0) dup2(err, 2);
      ::close(out[0]);
      ::close(out[1]);
      std::vector<char*> args;
      args.reserve(argv.size() + 1);
      for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
      args.push_back(nullptr);
      execv(args[0], args.data());
      _exit(127);
    }
    ::close(out[1]);
    out_fd_ = out[0];
  }
  ~WatchedProcess() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (out_fd_ >= 0) ::close(out_fd_);
  }
  WatchedProcess(const WatchedProcess&) = delete;
  WatchedProcess& operator=(const WatchedProcess&) = delete;

  // Read stdout until a line matches `pattern` (returns its match) or the timeout passes.
  std::smatch wait_for_line(const std::regex& pattern, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      std::size_t nl;
      while ((nl = buffer_.find('\n')) != std::string::npos) {
        lines_.push_back(buffer_.substr(0, nl));
        buffer_.erase(0, nl + 1);
        std::smatch m;
        if (std::regex_search(lines_.back(), m, pattern)) {
          matched_ = lines_.back();  // the smatch points into this string
          std::regex_search(matched_, m, pattern);
          return m;
        }
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
      if (left <= 0) throw std::runtime_error("timed out waiting for output; got: " + all_output());
      pollfd p{out_fd_, POLLIN, 0};
      if (poll(&p, 1, int(left)) <= 0) continue;
      char buf[512];
      const ssize_t n = read(out_fd_, buf, sizeof buf);
      if (n <= 0) throw std::runtime_error("process ended before the expected output; got: " + all_output());
      buffer_.append(buf, std::size_t(n));
    }
  }
  std::string all_output() const {
    std::string s;
    for (const auto& l : lines_) s += l + "\n";
    return s + buffer_;
  }
  void signal(int sig) const { ::kill(pid_, sig); }
  // Wait for the exit; returns the exit code, or 128 + signal.
  int wait() {
    int status = 0;
    waitpid(pid_, &status, 0);
    reaped_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  int out_fd_ = -1;
  bool reaped_ = false;
  std::string buffer_, matched_;
  std::vector<std::string> lines_;
};

// Start `palprig sim-rig` on 127.0.0.1:port (0: any free port) and return the port it got.
inline int start_sim_rig(std::unique_ptr<WatchedProcess>& child, const std::string& palprig, const std::string& rig,
                         int port, const std::string& write_log, const std::string& stderr_path,
                         const std::vector<std::string>& extra = {}) {
  std::vector<std::string> argv = {
      palprig, "sim-rig", "--rig", rig, "--listen", "127.0.0.1:" + std::to_string(port), "--write-log", write_log};
  argv.insert(argv.end(), extra.begin(), extra.end());
  child = std::make_unique<WatchedProcess>(argv, stderr_path);
  const auto m = child->wait_for_line(std::regex("listening on 127\\.0\\.0\\.1:([0-9]+)"), 10.0);
  const int got = std::stoi(m[1].str());
  child->wait_for_line(std::regex("serving 3 channels"), 10.0);
  return got;
}

// A copy of a rig file whose Modbus link(s) point at 127.0.0.1:port, with edits applied.
inline nlohmann::json rig_on_port(nlohmann::json rig, int port) {
  for (auto& link : rig["modbus"]["links"]) link["tcp"] = {{"host", "127.0.0.1"}, {"port", port}};
  return rig;
}

inline nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// A CSV file as rows of named columns (numbers; "nan" reads as NaN).
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::size_t col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    throw std::runtime_error("no column " + name);
  }
};

inline CsvTable read_csv(const std::string& path) {
  CsvTable t;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return t;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) t.header.push_back(cell);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::vector<double> row;
    for (std::string cell; std::getline(ss, cell, ',');) row.push_back(std::strtod(cell.c_str(), nullptr));
    if (row.size() == t.header.size()) row.shrink_to_fit(), t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace palprig::test_support
