#include "store/sqlite_read_access.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <sqlite3.h>

namespace palprig {

namespace {

bool exists(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0;
}

bool is_writable(const std::filesystem::path& p) { return ::access(p.c_str(), W_OK) == 0; }

}  // namespace

std::string sqlite_file_uri(const std::filesystem::path& file, const std::string& query) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::error_code ec;
  std::filesystem::path absolute = std::filesystem::absolute(file, ec);
  if (ec) absolute = file;
  // "file://" with an empty authority, then the absolute path: a path that itself starts with
  // "//" is not taken for a host name.
  std::string uri = "file://";
  for (const char ch : absolute.string()) {
    const auto c = static_cast<unsigned char>(ch);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '/' ||
                       c == '-' || c == '_' || c == '.' || c == '~';
    if (plain) {
      uri += ch;
    } else {
      uri += '%';
      uri += kHex[c >> 4];
      uri += kHex[c & 15];
    }
  }
  return uri + "?" + query;
}

ReadAccess plan_read_access(const std::filesystem::path& file) {
  const std::string name = file.string();
  const bool sidecars = exists(name + "-wal") || exists(name + "-shm");
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  ReadAccess a;
  if (!sidecars && !(is_writable(folder) && is_writable(file))) {
    a.immutable = true;
    a.uri = sqlite_file_uri(file, "mode=ro&immutable=1");
    return a;
  }
  a.uri = sqlite_file_uri(file, "mode=ro");
  a.tidy_sidecars = !sidecars;
  return a;
}

void tidy_reader_sidecars(const std::filesystem::path& file) noexcept {
  const std::string name = file.string(), wal = name + "-wal", shm = name + "-shm";
  if (!exists(wal) && !exists(shm)) return;
  // SQLite removes the two when the last connection closes, after checkpointing under an
  // EXCLUSIVE lock on the database file; a read-only connection cannot take that lock, so they
  // stay. Here a second, read-write connection takes the same lock without checkpointing:
  //   - locking_mode = EXCLUSIVE: its first read takes the EXCLUSIVE lock, which SQLite grants
  //     only when no other connection (any process, or this one) has the file open, and keeps
  //     the WAL index in its own memory, so it does not use the -shm either;
  //   - busy timeout 0: another connection is open (a writer started meanwhile): give up at once
  //     and leave the files to it;
  //   - SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE: closing never folds the WAL into the database.
  // Holding the lock, an empty -wal (0 bytes: no header, no frame, nothing any writer committed)
  // and the -shm are scratch files no-one else has open: they are removed. A -wal with frames (a
  // writer came and went while this reader read) is left for the next writer to fold.
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(name.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr) == SQLITE_OK &&
      sqlite3_db_readonly(db, "main") == 0) {
    sqlite3_db_config(db, SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
    sqlite3_busy_timeout(db, 0);
    if (sqlite3_exec(db, "PRAGMA locking_mode = EXCLUSIVE; SELECT count(*) FROM sqlite_master", nullptr, nullptr,
                     nullptr) == SQLITE_OK) {
      struct stat st {};
      const bool empty_wal = ::stat(wal.c_str(), &st) != 0 || st.st_size == 0;
      if (empty_wal) {
        ::unlink(wal.c_str());
        ::unlink(shm.c_str());
      }
    }
  }
  sqlite3_close(db);
}

}  // namespace palprig
