#pragma once
// How a reader (stats, export, store copy's source, the window's statistics) opens a trial
// database so that it never writes to it: SQLITE_OPEN_READONLY (`mode=ro`), which can neither
// write a page nor checkpoint, so a -wal left by a crashed writer is read and left as it was.
//
// A read-only connection to a WAL database needs the -wal and -shm files beside it (SQLite,
// "WAL mode", section "Read-Only Databases": they must exist, or the folder must let SQLite
// create them, or the connection must be `immutable`). What a reader does therefore depends on
// what it finds before opening:
//
//   -wal or -shm present (a writer is running, or one crashed): `mode=ro` on them. Nothing of
//     them is removed afterwards; they are the writer's.
//   neither present (the last writer closed cleanly; every page is in the database file):
//     - this process may write the folder and the file: `mode=ro`, which creates an empty -wal
//       and a -shm; after closing, tidy_reader_sidecars() removes the two again, but only under
//       SQLite's own proof that no other connection has the file open (see there), so a reader
//       leaves a cleanly closed database as it found it.
//     - otherwise (a read-only folder, or a file another user owns): `mode=ro&immutable=1`.
//       SQLite could not create the two files (the open would fail), and must not: a -wal and
//       -shm owned by this user would keep the owner's next session from writing them. Immutable
//       is safe while no-one writes the database file during the read; only another user with
//       write permission could, and only a checkpoint (which rewrites pages) would tear the
//       read, so the connection checks the file's identity when a statement finishes and
//       refuses a read that overlapped a change (Database::refuse_if_changed_during_read).
#include <filesystem>
#include <string>

namespace palprig {

struct ReadAccess {
  std::string uri;             // file:...?mode=ro[&immutable=1], for sqlite3_open_v2 with SQLITE_OPEN_URI
  bool immutable = false;      // no locks, no -wal/-shm: see above
  bool tidy_sidecars = false;  // neither -wal nor -shm existed: remove the ones the connection made
};

ReadAccess plan_read_access(const std::filesystem::path& file);

// After the reader's connection is closed: when no other connection has the database open and
// its -wal holds no frame, removes the -wal and -shm. Leaves them otherwise. Never throws.
void tidy_reader_sidecars(const std::filesystem::path& file) noexcept;

// `file` as an SQLite URI path ("file:///abs/path", with %, ?, # and non-printing bytes
// percent-encoded) followed by `query` ("mode=ro").
std::string sqlite_file_uri(const std::filesystem::path& file, const std::string& query);

}  // namespace palprig
