#include "gui/free_file_name.hpp"

#include <string>
#include <system_error>

namespace palprig::gui {

std::filesystem::path first_free_file(const std::filesystem::path& wanted) {
  std::filesystem::path p = wanted;
  std::error_code ec;
  // symlink_status: a dangling link is taken too (writing through it would create its target).
  for (int n = 2; std::filesystem::exists(std::filesystem::symlink_status(p, ec)); ++n)
    p = wanted.parent_path() / (wanted.stem().string() + "-" + std::to_string(n) + wanted.extension().string());
  return p;
}

}  // namespace palprig::gui
