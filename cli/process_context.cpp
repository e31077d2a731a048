// What every command shares with the process: the folder of the shipped data. Kept out of main.cpp so that the commands
// depend on this file, not on the one that registers them.
#include <cstdlib>

#include "cli/commands.hpp"

namespace palprig::cli {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("PALPRIG_DATA")) return env;
  return PALPRIG_SOURCE_DATA_DIR;
}

}  // namespace palprig::cli
