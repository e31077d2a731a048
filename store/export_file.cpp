#include "store/export_file.hpp"

#include <system_error>

#include "core/input_error.hpp"

namespace palprig {

void write_export_json(const std::filesystem::path& path, const nlohmann::ordered_json& json,
                       std::vector<std::filesystem::path>& written) {
  ExportFile file(path);
  file << json.dump(2) << "\n";
  commit_into(file, written);
}

void make_export_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(dir.string(), "`out_dir`", "a folder that can be created");
}

}  // namespace palprig
