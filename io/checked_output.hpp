#pragma once
// The one door through which palprig writes a file (maps, scenes, telemetry CSV, charts,
// calibration files and traces): every write and the close are checked, and a file that could not
// be written whole is never left looking complete.
//
// A regular file or a new path is written to a temporary file beside it (same folder, so the
// rename is atomic; named ".NAME.XXXXXX.partial"), synced, and renamed over the path only when
// every byte and the close succeeded; otherwise the temporary is removed and the path is left
// as it was (absent, or the earlier file). A device or FIFO given as the path (/dev/stdout,
// /dev/full, a pipe) cannot be renamed over: it is written directly, each write checked.
//
// A failure throws OutputError: "FILE: cannot write: REASON" with the system's reason
// (strerror: "No space left on device", "Permission denied", "Read-only file system"), which
// the command line prints as one line with exit 1 (the machine, not the input).
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace palprig {

class OutputError : public Error {
 public:
  OutputError(const std::filesystem::path& file, const std::string& reason)
      : Error(file.string() + ": cannot write: " + reason), file_(file) {}
  const std::filesystem::path& file() const noexcept { return file_; }

 private:
  std::filesystem::path file_;
};

class CheckedOutputFile {
 public:
  // Opens the temporary (or the device). Throws OutputError naming `path` (a folder that does
  // not exist or may not be written, a path that is a directory).
  explicit CheckedOutputFile(const std::filesystem::path& path);
  // Without commit(): the temporary is removed, the path left as it was.
  ~CheckedOutputFile();
  CheckedOutputFile(const CheckedOutputFile&) = delete;
  CheckedOutputFile& operator=(const CheckedOutputFile&) = delete;

  // Buffered; the first failed write is remembered (the stream goes bad) and thrown by commit().
  std::ostream& stream() noexcept;
  void write(std::string_view bytes);
  // Flushes, syncs and closes; renames the temporary over the path. Throws OutputError with the
  // first failure's reason (the temporary removed).
  void commit();
  // The same, with `check` run on the complete temporary file before the rename (a writer that
  // reads back what it wrote); when it throws, the temporary is removed, the path left as it was
  // and the exception passed on. Not run for a device, which has no temporary.
  void commit(const std::function<void(const std::filesystem::path& written)>& check);
  const std::filesystem::path& path() const noexcept { return path_; }

 private:
  class Buffer;
  std::filesystem::path path_, temporary_;  // temporary_ empty: writing the device directly
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> stream_;
  bool committed_ = false;
};

// The whole of `bytes` as the file `path`, through CheckedOutputFile.
void write_file_checked(const std::filesystem::path& path, std::string_view bytes);

}  // namespace palprig
