// A read-only trial store (stats, export, the GUI's statistics view) reads without changing the
// database and, when it is the last connection to close, leaves no -wal/-shm files behind: an
// SQLITE_OPEN_READONLY connection cannot delete them itself, so each `palprig stats trials` after
// a session once left two stray files beside the database; the reader now removes the empty
// ones its connection made, under SQLite's EXCLUSIVE lock (store/sqlite_read_access.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "store/trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool has_wal_files(const std::filesystem::path& db) {
  return std::filesystem::exists(db.string() + "-wal") || std::filesystem::exists(db.string() + "-shm");
}

TEST(ReadOnlyStore, StatsAndExportLeaveTheDatabaseAsTheyFoundIt) {
  ScratchDir dir;
  const std::filesystem::path db = dir / "trials.db";
  const auto run =
      run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "discrimination_002.json").string(),
                   "--participant", "sim:4", "--db", db.string(), "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_FALSE(has_wal_files(db)) << "the writer closed cleanly";
  const std::string before = file_bytes(db);

  const auto stats = run_palprig({"stats", "trials", db.string(), "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_FALSE(has_wal_files(db)) << "stats trials left -wal/-shm beside " << db;
  const auto csv = run_palprig({"export", db.string(), "--format", "csv", "--out", (dir / "csv").string()});
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_FALSE(has_wal_files(db)) << "export left -wal/-shm beside " << db;
  EXPECT_EQ(file_bytes(db), before) << "a read-only store changed the database file";
}

TEST(ReadOnlyStore, RefusesEveryWrite) {
  ScratchDir dir;
  const std::filesystem::path db = dir / "trials.db";
  const auto run =
      run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "discrimination_002.json").string(),
                   "--participant", "sim:5", "--db", db.string(), "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string before = file_bytes(db);
  {
    const auto store = open_trial_store(db.string(), TrialStore::Access::read_only);
    const auto trials = store->read_trials(true);
    ASSERT_FALSE(trials.empty());
    EXPECT_ANY_THROW(store->complete_session(trials.front().session));
  }
  EXPECT_EQ(file_bytes(db), before);
  EXPECT_FALSE(has_wal_files(db));
}

}  // namespace
}  // namespace palprig
