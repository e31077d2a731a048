// What every command shares with the process: the folder of the shipped data. Kept out of main.cpp so that the commands
// depend on this file, not on the one that registers them.
#include <cstdlib>

#include "cli/commands.hpp"
#include "cli/data_files.hpp"

namespace palprig::cli {

std::filesystem::path data_dir() { return shipped_data_place().dir; }

}  // namespace palprig::cli
