#pragma once
// One file of an export, written so that a reader never finds a short file that looks
// complete: the text goes to NAME.partial beside the target, and commit() flushes, checks every
// write and the close, and renames it into place; a file that was not committed (a write
// failed, the disk filled, an exception left the export) is removed. A failed write or close is
// std::runtime_error naming the file and the system's reason (exit 1 in the command line).
// Written by hand: the standard streams report a failed write only as a sticky bit, and SQLite's
// and Qt's savers do not write our text formats.
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <string>

namespace palprig {

class ExportFile {
 public:
  explicit ExportFile(std::filesystem::path path);
  ~ExportFile();
  ExportFile(const ExportFile&) = delete;
  ExportFile& operator=(const ExportFile&) = delete;

  template <class T>
  ExportFile& operator<<(const T& value) {
    out_ << value;
    if (!out_ && error_ == 0) error_ = errno;  // the reason, before anything else overwrites it
    return *this;
  }
  // Throws when a write since the last check failed (long exports call it now and then, so a
  // full disk ends the export early rather than after every row was formatted).
  void check();
  // Flushes, closes and renames into place; throws std::runtime_error when any of it failed.
  void commit();
  const std::filesystem::path& path() const noexcept { return path_; }

 private:
  [[noreturn]] void fail(const std::string& what);

  std::filesystem::path path_, partial_;
  std::ofstream out_;
  bool committed_ = false;
  int error_ = 0;  // errno of the first failed write
};

// Creates `dir` (and its parents) when missing; InputError when it cannot be a folder.
void make_export_dir(const std::filesystem::path& dir);

}  // namespace palprig
