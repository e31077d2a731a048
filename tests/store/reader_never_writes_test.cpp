// Readers (stats, export, store copy's source) never write: they open SQLITE_OPEN_READONLY, read
// a -wal a crashed writer left without folding it into the database (it stays byte for byte,
// damaged or not), read a database in a folder they may not write, and still leave a cleanly
// closed database without -wal/-shm files (store/sqlite_read_access.hpp).
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "store/sqlite_db.hpp"
#include "store/trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

std::string bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool present(const std::filesystem::path& p) { return std::filesystem::exists(p); }

std::filesystem::path wal_of(const std::filesystem::path& db) { return db.string() + "-wal"; }
std::filesystem::path shm_of(const std::filesystem::path& db) { return db.string() + "-shm"; }

// Root reads and writes through permission bits: as in store_environment_test.cpp, the reader
// then runs as nobody, for whom a folder of mode 0555 is read-only.

void make_store(const std::filesystem::path& db) {
  const auto run =
      run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "discrimination_002.json").string(),
                   "--participant", "sim:4", "--db", db.string(), "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_FALSE(present(wal_of(db)) || present(shm_of(db))) << "the writer closed cleanly";
}

// A writer that commits `sql` and dies without closing (no checkpoint at close): its -wal, with
// the commit in it, and its -shm stay beside the database, as after a crash.
void crash_a_writer_after(const std::filesystem::path& db, const std::string& sql) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    sqlite3* c = nullptr;
    if (sqlite3_open(db.c_str(), &c) != SQLITE_OK) ::_exit(3);
    if (sqlite3_exec(c, ("PRAGMA wal_autocheckpoint = 0; " + sql).c_str(), nullptr, nullptr, nullptr) != SQLITE_OK)
      ::_exit(4);
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the crashing writer could not commit";
  ASSERT_TRUE(present(wal_of(db)));
  ASSERT_GT(std::filesystem::file_size(wal_of(db)), 0u);
}

// The crashed writer removed the three-finger condition's trials; only its -wal knows.
constexpr const char* kCrashEdit = "DELETE FROM trials WHERE condition = 'three-finger'";

TEST(ReaderNeverWrites, ACrashedWritersWalIsReadAndKeptByteForByte) {
  ScratchDir dir;
  const auto db = dir / "trials.db";
  make_store(db);
  crash_a_writer_after(db, kCrashEdit);
  const std::string db_before = bytes_of(db), wal_before = bytes_of(wal_of(db));

  const auto stats = run_palprig({"stats", "trials", db.string()});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("single-finger"), std::string::npos) << stats.out;
  EXPECT_EQ(stats.out.find("three-finger"), std::string::npos) << "the -wal's commit was not read: " << stats.out;
  const auto csv = run_palprig({"export", db.string(), "--format", "csv", "--out", (dir / "csv").string()});
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const auto copy = run_palprig({"store", "copy", "--from", db.string(), "--to", (dir / "copy.db").string()});
  ASSERT_EQ(copy.exit_code, 0) << copy.err;

  EXPECT_TRUE(bytes_of(db) == db_before) << "a reader wrote into the database";
  ASSERT_TRUE(present(wal_of(db))) << "a reader removed the crashed writer's -wal";
  EXPECT_TRUE(bytes_of(wal_of(db)) == wal_before) << "a reader changed the crashed writer's -wal";
}

TEST(ReaderNeverWrites, ADamagedWalIsReadUpToItsLastWholeCommitAndKept) {
  ScratchDir dir;
  const auto db = dir / "trials.db";
  make_store(db);
  crash_a_writer_after(db, kCrashEdit);
  // The writer died half-way through writing its last frame.
  std::filesystem::resize_file(wal_of(db), std::filesystem::file_size(wal_of(db)) - 1000);
  const std::string db_before = bytes_of(db), wal_before = bytes_of(wal_of(db));

  const auto stats = run_palprig({"stats", "trials", db.string()});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("three-finger"), std::string::npos) << "the torn commit was read: " << stats.out;
  EXPECT_TRUE(bytes_of(db) == db_before) << "a reader folded a damaged -wal into the database";
  ASSERT_TRUE(present(wal_of(db)));
  EXPECT_TRUE(bytes_of(wal_of(db)) == wal_before) << "a reader changed a damaged -wal";
}

TEST(ReaderNeverWrites, AStoreInAReadOnlyFolderIsRead) {
  ScratchDir dir;
  const auto folder = dir / "archive";
  std::filesystem::create_directory(folder);
  const auto db = folder / "trials.db";
  make_store(db);
  const auto expected = run_palprig({"stats", "trials", db.string()});
  ASSERT_EQ(expected.exit_code, 0) << expected.err;
  ASSERT_FALSE(present(wal_of(db)));
  ::chmod(folder.c_str(), 0555);
  const auto out = dir / "out";
  std::filesystem::create_directory(out);
  ::chmod(out.c_str(), 0777);
  const std::string before = bytes_of(db);

  const auto stats = test_support::run_process(palprig::testing::as_unprivileged() + test_support::palprig_bin() +
                                               " stats trials " + db.string());
  EXPECT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_EQ(stats.out, expected.out);
  const auto csv =
      test_support::run_process(palprig::testing::as_unprivileged() + test_support::palprig_bin() + " export " +
                                db.string() + " --format csv --out " + (out / "csv").string());
  EXPECT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_TRUE(present(out / "csv" / "trials_long.csv"));
  EXPECT_FALSE(present(wal_of(db)) || present(shm_of(db)));
  EXPECT_TRUE(bytes_of(db) == before);
  ::chmod(folder.c_str(), 0755);
}

TEST(ReaderNeverWrites, ACrashedWriterInAReadOnlyFolderIsReadWithItsWal) {
  ScratchDir dir;
  const auto folder = dir / "archive";
  std::filesystem::create_directory(folder);
  const auto db = folder / "trials.db";
  make_store(db);
  crash_a_writer_after(db, kCrashEdit);
  ::chmod(folder.c_str(), 0555);
  const std::string db_before = bytes_of(db), wal_before = bytes_of(wal_of(db));

  const auto stats = test_support::run_process(palprig::testing::as_unprivileged() + test_support::palprig_bin() +
                                               " stats trials " + db.string());
  EXPECT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("single-finger"), std::string::npos) << stats.out;
  EXPECT_EQ(stats.out.find("three-finger"), std::string::npos) << "the -wal's commit was not read: " << stats.out;
  EXPECT_TRUE(bytes_of(db) == db_before);
  EXPECT_TRUE(bytes_of(wal_of(db)) == wal_before);
  ::chmod(folder.c_str(), 0755);
}

TEST(ReaderNeverWrites, AReaderBesideAnOpenWriterLeavesTheWritersFiles) {
  ScratchDir dir;
  const auto db = dir / "trials.db";
  make_store(db);
  {
    // A session still running in this process (the window's live statistics read beside it).
    Database writer(db, Database::Mode::read_write_create);
    writer.exec("SELECT count(*) FROM trials");
    {
      const auto reader = open_trial_store(db.string(), TrialStore::Access::read_only);
      EXPECT_FALSE(reader->read_trials(true).empty());
    }
    EXPECT_TRUE(present(wal_of(db))) << "the reader removed the running writer's -wal";
    writer.exec("UPDATE trials SET response_time_s = response_time_s");  // the writer goes on writing
  }
  // The writer, last to close, checkpointed and removed its files as SQLite does.
  EXPECT_FALSE(present(wal_of(db)) || present(shm_of(db)));
  const auto stats = run_palprig({"stats", "trials", db.string()});
  EXPECT_EQ(stats.exit_code, 0) << stats.err;
}

}  // namespace
}  // namespace palprig
