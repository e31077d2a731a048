#include "store/export_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "models/parse_error.hpp"

namespace palprig {

ExportFile::ExportFile(std::filesystem::path path) : path_(std::move(path)), partial_(path_.string() + ".partial") {
  errno = 0;
  out_.open(partial_, std::ios::binary | std::ios::trunc);
  if (!out_) fail("cannot be created");
}

ExportFile::~ExportFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(partial_, ignored);
}

void ExportFile::fail(const std::string& what) {
  const int error = error_ != 0 ? error_ : errno;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(partial_, ignored);
  committed_ = true;  // nothing left to remove
  throw std::runtime_error(path_.string() + ": " + what + (error ? std::string(" (") + std::strerror(error) + ")" : "") +
                           "; the export is incomplete");
}

void ExportFile::check() {
  if (!out_) fail("a write failed");
}

void ExportFile::commit() {
  if (!out_) fail("a write failed");
  errno = 0;
  out_.flush();
  if (!out_) fail("a write failed");
  out_.close();  // the last buffered bytes reach the file here: a full disk can show only now
  if (out_.fail()) fail("closing it failed");
  std::error_code ec;
  std::filesystem::rename(partial_, path_, ec);
  if (ec) {
    errno = ec.value();
    fail("renaming the finished file into place failed");
  }
  committed_ = true;
}

void make_export_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw InputError(dir.string(), "`out_dir`", "a folder that can be created");
}

}  // namespace palprig
