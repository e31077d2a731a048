#pragma once
// One file of an export, through io/checked_output.hpp (the one checked writer): the text
// goes to a temporary beside the target and is renamed into place only when every write and the
// close succeeded; a file that was not committed is removed. A failed write is OutputError
// ("FILE: cannot write: REASON", exit 1 in the command line), and no short file looks complete.
// This adapter only adds `<<` for the exporters' mixed values and a periodic check.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/checked_output.hpp"

namespace palprig {

class ExportFile {
 public:
  explicit ExportFile(const std::filesystem::path& path) : file_(path) {}

  template <class T>
  ExportFile& operator<<(const T& value) {
    file_.stream() << value;
    return *this;
  }
  // Long exports call it now and then, so a full disk ends the export early rather than after
  // every row was formatted (the reason is the first failed write's, as commit() gives it).
  void check() {
    if (!file_.stream()) file_.commit();  // throws OutputError with the first failure's reason
  }
  void commit() { file_.commit(); }
  const std::filesystem::path& path() const noexcept { return file_.path(); }

 private:
  CheckedOutputFile file_;
};

// Commits `file` and adds it to `written` (the export's list of files, in order).
inline void commit_into(ExportFile& file, std::vector<std::filesystem::path>& written) {
  file.commit();
  written.push_back(file.path());
}

// A JSON document (a BIDS sidecar, dataset_description.json) as `path`, checked, added to `written`.
void write_export_json(const std::filesystem::path& path, const nlohmann::ordered_json& json,
                       std::vector<std::filesystem::path>& written);

// Creates `dir` (and its parents) when missing; InputError when it cannot be a folder.
void make_export_dir(const std::filesystem::path& dir);

}  // namespace palprig
