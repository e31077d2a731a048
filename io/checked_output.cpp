#include "io/checked_output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <streambuf>
#include <vector>

namespace palprig {

// A stream buffer over a file descriptor that keeps the first error (errno) of any write.
class CheckedOutputFile::Buffer final : public std::streambuf {
 public:
  explicit Buffer(int fd) : fd_(fd), space_(1 << 16) { setp(space_.data(), space_.data() + space_.size()); }
  ~Buffer() override { close_quietly(); }

  int error() const noexcept { return error_; }
  // Flush what is buffered, fsync (regular files: the rename must not reach the disk before
  // the data), close. The first error is kept.
  void finish(bool sync_to_disk) {
    drain();
    if (error_ == 0 && sync_to_disk && ::fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) error_ = errno;
    if (fd_ >= 0 && ::close(fd_) != 0 && error_ == 0) error_ = errno;
    fd_ = -1;
  }
  void close_quietly() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n > epptr() - pptr()) {
      if (!drain()) return 0;
      if (n >= static_cast<std::streamsize>(space_.size())) return write_all(s, static_cast<std::size_t>(n)) ? n : 0;
    }
    std::memcpy(pptr(), s, static_cast<std::size_t>(n));
    pbump(static_cast<int>(n));
    return n;
  }

 private:
  bool drain() {
    const auto n = static_cast<std::size_t>(pptr() - pbase());
    setp(space_.data(), space_.data() + space_.size());
    return n == 0 ? error_ == 0 : write_all(space_.data(), n);
  }
  bool write_all(const char* s, std::size_t n) {
    if (error_ != 0) return false;
    while (n > 0) {
      const ssize_t w = ::write(fd_, s, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        error_ = w < 0 ? errno : EIO;
        return false;
      }
      s += w;
      n -= static_cast<std::size_t>(w);
    }
    return true;
  }

  int fd_;
  std::vector<char> space_;
  int error_ = 0;
};

namespace {

std::string reason(int error) { return std::strerror(error); }

std::filesystem::path temporary_beside(const std::filesystem::path& path, std::mt19937_64& random) {
  static constexpr char kLetters[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::string suffix;
  for (int i = 0; i < 6; ++i) suffix += kLetters[random() % (sizeof kLetters - 1)];
  return path.parent_path() / ("." + path.filename().string() + "." + suffix + ".partial");
}

}  // namespace

CheckedOutputFile::CheckedOutputFile(const std::filesystem::path& path) : path_(path) {
  if (path_.filename().empty()) throw OutputError(path_, "a file name is needed, not a folder");
  struct stat st {};
  const bool exists = ::stat(path_.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw OutputError(path_, reason(EISDIR));
  int fd = -1;
  if (exists && !S_ISREG(st.st_mode)) {
    // A device or a FIFO: written in place (O_NONBLOCK is not used: a FIFO's reader decides).
    fd = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) throw OutputError(path_, reason(errno));
  } else {
    // Mode: that of the file replaced, or what a new file gets under the umask.
    const mode_t mode = exists ? (st.st_mode & 07777) : 0666;
    std::mt19937_64 random(std::random_device{}());
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
      temporary_ = temporary_beside(path_, random);
      fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOCTTY | O_CLOEXEC, mode);
      if (fd < 0 && errno != EEXIST) {
        const int error = errno;
        // Name the folder when it is the folder that refuses.
        const std::filesystem::path folder = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
        if (error == ENOENT) throw OutputError(path_, "its folder " + folder.string() + " does not exist");
        if (error == EACCES || error == EROFS)
          throw OutputError(path_, reason(error) + " (its folder " + folder.string() + " may not be written)");
        throw OutputError(path_, reason(error));
      }
    }
    if (fd < 0) throw OutputError(path_, reason(EEXIST));
    if (exists) ::fchmod(fd, mode);  // the umask does not narrow a replaced file's mode
  }
  buffer_ = std::make_unique<Buffer>(fd);
  stream_ = std::make_unique<std::ostream>(buffer_.get());
}

CheckedOutputFile::~CheckedOutputFile() {
  if (committed_) return;
  stream_.reset();
  if (buffer_) buffer_->close_quietly();
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

std::ostream& CheckedOutputFile::stream() noexcept { return *stream_; }

void CheckedOutputFile::write(std::string_view bytes) {
  stream_->write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void CheckedOutputFile::commit() { commit(nullptr); }

void CheckedOutputFile::commit(const std::function<void(const std::filesystem::path& written)>& check) {
  stream_->flush();
  buffer_->finish(!temporary_.empty());
  const int error = buffer_->error() != 0 ? buffer_->error() : (stream_->bad() ? EIO : 0);
  if (error != 0) {
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
    committed_ = true;  // nothing left to remove
    throw OutputError(path_, reason(error));
  }
  if (check && !temporary_.empty()) {
    try {
      check(temporary_);
    } catch (...) {
      ::unlink(temporary_.c_str());
      committed_ = true;
      throw;
    }
  }
  if (!temporary_.empty() && ::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    ::unlink(temporary_.c_str());
    committed_ = true;
    throw OutputError(path_, reason(e));
  }
  committed_ = true;
}

void write_file_checked(const std::filesystem::path& path, std::string_view bytes) {
  CheckedOutputFile out(path);
  out.write(bytes);
  out.commit();
}

}  // namespace palprig
