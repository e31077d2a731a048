#include "store/integrity_check_cache.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <vector>

namespace palprig {

namespace {

std::int64_t ns(const timespec& t) { return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec; }

std::string describe(const struct stat& st) {
  return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + " " + std::to_string(st.st_size) + " " +
         std::to_string(ns(st.st_mtim)) + " " + std::to_string(ns(st.st_ctim));
}

// A state is remembered only once its newest change is this old: file times are kept at the
// file system's granularity (a clock tick; 1-2 s on some file systems), so a write in the same
// tick as the check could otherwise leave every mark as it was.
constexpr std::int64_t kSettledNs = 2'000'000'000;

std::int64_t newest_change_ns(const struct stat& db, const struct stat* wal) {
  std::int64_t newest = std::max(ns(db.st_mtim), ns(db.st_ctim));
  if (wal) newest = std::max({newest, ns(wal->st_mtim), ns(wal->st_ctim)});
  return newest;
}

std::vector<std::string> cached_lines(const std::filesystem::path& cache) {
  std::vector<std::string> lines;
  std::ifstream in(cache);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

}  // namespace

std::optional<StoreFileState> store_file_state(const std::filesystem::path& file) {
  struct stat db {};
  if (::stat(file.c_str(), &db) != 0 || !S_ISREG(db.st_mode)) return std::nullopt;
  // An empty -wal holds no page (a reader's connection makes one beside a cleanly closed file and
  // removes it again): the state is the database file's alone.
  struct stat wal {};
  const bool has_wal = ::stat((file.string() + "-wal").c_str(), &wal) == 0 && wal.st_size > 0;
  StoreFileState s{"db " + describe(db) + " wal " + (has_wal ? describe(wal) : std::string("none"))};
  timespec now{};
  ::clock_gettime(CLOCK_REALTIME, &now);
  // Not yet settled: report a state no cache line can equal, so it is checked and not kept.
  if (ns(now) - newest_change_ns(db, has_wal ? &wal : nullptr) < kSettledNs) s.text = "unsettled " + s.text;
  return s;
}

std::filesystem::path integrity_cache_file() {
  std::filesystem::path base;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/') {
    base = xdg;
  } else if (const char* home = std::getenv("HOME"); home && *home == '/') {
    base = std::filesystem::path(home) / ".cache";
  } else {
    return {};
  }
  return base / "palprig" / "sound-stores";
}

bool known_sound(const StoreFileState& state) {
  if (state.text.starts_with("unsettled")) return false;
  const std::filesystem::path cache = integrity_cache_file();
  if (cache.empty()) return false;
  const std::vector<std::string> lines = cached_lines(cache);
  return std::find(lines.begin(), lines.end(), state.text) != lines.end();
}

void remember_sound(const StoreFileState& state) noexcept {
  try {
    if (state.text.starts_with("unsettled")) return;
    const std::filesystem::path cache = integrity_cache_file();
    if (cache.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(cache.parent_path(), ec);
    if (ec) return;
    std::vector<std::string> lines = cached_lines(cache);
    std::erase(lines, state.text);
    lines.push_back(state.text);
    if (lines.size() > kMaxIntegrityCacheEntries)
      lines.erase(lines.begin(), lines.end() - static_cast<std::ptrdiff_t>(kMaxIntegrityCacheEntries));
    std::string text;
    for (const std::string& line : lines) text += line + "\n";
    // A new file beside the cache, renamed over it: another reader sees the old or the new list.
    std::string tmp = (cache.parent_path() / "sound-stores.XXXXXX").string();
    const int fd = ::mkstemp(tmp.data());
    if (fd < 0) return;
    bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
    ok = ::close(fd) == 0 && ok;
    if (!ok || ::rename(tmp.c_str(), cache.c_str()) != 0) ::unlink(tmp.c_str());
  } catch (...) {
    // Only a cache: the next reader checks again.
  }
}

}  // namespace palprig
