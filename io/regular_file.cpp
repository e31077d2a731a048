#include "io/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/input_error.hpp"

namespace palprig {

namespace {

std::string kind_of(const struct stat& st) {
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

std::string problem_of(const struct stat& st, std::uintmax_t max_bytes) {
  if (!S_ISREG(st.st_mode)) return kind_of(st);
  if (st.st_size < 0 || std::uintmax_t(st.st_size) > max_bytes) return std::to_string(st.st_size) + " bytes";
  return "";
}

std::string errno_text(int error) {
  if (error == ENOENT) return "no such file";
  return std::string("cannot open it: ") + std::strerror(error);
}

[[noreturn]] void refuse(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what,
                         const std::string& problem) {
  throw InputError(path.string(), "file",
                   "a regular file of at most " + file_size_text(max_bytes) + " holding " + what + ", got " + problem);
}

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string file_size_text(std::uintmax_t bytes) {
  if (bytes >= kMiB && bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
  if (bytes >= 1024 && bytes % 1024 == 0) return std::to_string(bytes / 1024) + " KiB";
  return std::to_string(bytes) + " bytes";
}

std::string regular_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return errno_text(errno);
  return problem_of(st, max_bytes);
}

std::string read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what) {
  // stat first, so nothing but a regular file is ever opened (opening some devices acts);
  // then fstat the descriptor actually read, in case the name changed in between.
  if (const std::string p = regular_file_problem(path, max_bytes); !p.empty()) refuse(path, max_bytes, what, p);
  Fd f;
  f.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (f.fd < 0) refuse(path, max_bytes, what, errno_text(errno));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) refuse(path, max_bytes, what, errno_text(errno));
  if (const std::string p = problem_of(st, max_bytes); !p.empty()) refuse(path, max_bytes, what, p);
  std::string out;
  out.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(f.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuse(path, max_bytes, what, std::string("a read error: ") + std::strerror(errno));
    if (n == 0) break;
    if (out.size() + std::size_t(n) > max_bytes) refuse(path, max_bytes, what, "a file that grew past that while read");
    out.append(buffer, std::size_t(n));
  }
  return out;
}

std::ifstream open_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what,
                                std::ios::openmode mode) {
  if (const std::string p = regular_file_problem(path, max_bytes); !p.empty()) refuse(path, max_bytes, what, p);
  std::ifstream in(path, mode);
  if (!in) refuse(path, max_bytes, what, errno_text(errno));
  return in;
}

}  // namespace palprig
