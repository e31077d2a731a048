// What every command shares with the process: the stop flag set by SIGINT/SIGTERM and the
// folder of the shipped data. Kept out of main.cpp so that the commands depend on this file,
// not on the one that registers them.
#include <csignal>
#include <cstdlib>

#include "cli/commands.hpp"
#include "cli/data_files.hpp"

namespace palprig::cli {

std::atomic<int>& stop_signal() {
  static std::atomic<int> flag{0};
  return flag;
}

extern "C" void palprig_on_stop_signal(int sig) { stop_signal().store(sig); }

void install_stop_signals() {
  std::signal(SIGINT, palprig_on_stop_signal);
  std::signal(SIGTERM, palprig_on_stop_signal);
}

std::filesystem::path data_dir() { return shipped_data_place().dir; }

}  // namespace palprig::cli
