// Damaged trial databases, made for real: a file truncated mid-page, a page overwritten with
// garbage, a stored protocol that no longer parses. Every command that opens such a file
// refuses it with one line naming the file (exit 2), writes nothing into it, and never
// substitutes data (no statistics from the readable part, no made-up finger names).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

using testing::CommandResult;
using testing::count_lines;
using testing::run_palprig;
using testing::ScratchDir;

// A real database of `sessions` completed simulated sessions (32 trials each).
std::string make_store(const ScratchDir& dir, int sessions) {
  std::string db = (dir / "study.db").string();
  for (int i = 1; i <= sessions; ++i) {
    const auto r = run_palprig({"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(),
                                "--participant", "sim:" + std::to_string(i), "--db", db, "--quiet"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  // The last writer checkpointed and removed the WAL, so the damage below hits the only copy.
  EXPECT_FALSE(std::filesystem::exists(db + "-wal"));
  return db;
}

std::string bytes_of(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void overwrite_page_with_garbage(const std::string& file, std::size_t page_number, std::size_t page_size) {
  std::mt19937 random(20261123);
  std::string garbage(page_size, '\0');
  for (char& c : garbage) c = static_cast<char>(random() & 0xff);
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>((page_number - 1) * page_size));
  f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
}

void exec_sql(const std::string& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string message = error ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << message;
}

// One line on stderr naming the file; exit 2; nothing on stdout (no partial results).
void expect_refused_as_damaged(const CommandResult& r, const std::string& db) {
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(db), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("undamaged"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("Se"), std::string::npos) << "statistics were printed from a damaged file: " << r.out;
}

void expect_every_command_refuses(const ScratchDir& dir, const std::string& db) {
  expect_refused_as_damaged(run_palprig({"stats", "trials", db}), db);
  expect_refused_as_damaged(run_palprig({"stats", "trials", db, "--json"}), db);
  expect_refused_as_damaged(run_palprig({"export", db, "--out", (dir / "csv").string()}), db);
  EXPECT_FALSE(std::filesystem::exists(dir / "csv" / "trials_long.csv"));

  // A new session would be written into the damaged file: refused, and the file is untouched.
  const std::string before = bytes_of(db);
  const auto run = run_palprig({"experiment", "run", "--protocol", palprig::testing::discrimination_protocol_file(),
                                "--participant", "sim:99", "--db", db, "--quiet"});
  expect_refused_as_damaged(run, db);
  EXPECT_EQ(run.out.find("session"), std::string::npos) << "a session was started: " << run.out;
  EXPECT_TRUE(bytes_of(db) == before) << "the damaged database was written to";
  EXPECT_FALSE(std::filesystem::exists(db + "-wal") && std::filesystem::file_size(db + "-wal") > 0);
}

TEST(DamagedStore, TruncatedMidPageIsRefusedNotHalfCounted) {
  ScratchDir dir;
  const std::string db = make_store(dir, 4);
  const auto size = std::filesystem::file_size(db);
  // A few KB short, not on a page boundary (a copy cut off, a disk full while copying).
  std::filesystem::resize_file(db, size - 1000);
  expect_every_command_refuses(dir, db);
}

TEST(DamagedStore, TruncatedByWholePagesIsRefused) {
  ScratchDir dir;
  const std::string db = make_store(dir, 4);
  std::filesystem::resize_file(db, std::filesystem::file_size(db) - std::uintmax_t{2} * 4096);
  expect_every_command_refuses(dir, db);
}

TEST(DamagedStore, PageOfGarbageIsRefusedWithTheFileName) {
  ScratchDir dir;
  const std::string db = make_store(dir, 4);
  const std::size_t pages = std::filesystem::file_size(db) / 4096;
  ASSERT_GE(pages, 8u);
  overwrite_page_with_garbage(db, pages - 2, 4096);  // among the trials' pages
  expect_every_command_refuses(dir, db);
}

TEST(DamagedStore, GarbageInTheSchemaPageIsRefused) {
  ScratchDir dir;
  const std::string db = make_store(dir, 1);
  // Page 1 after its 100-byte header: sqlite_master itself.
  std::mt19937 random(7);
  std::string garbage(4096 - 100, '\0');
  for (char& c : garbage) c = static_cast<char>(random() & 0xff);
  std::fstream f(db, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(100);
  f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  f.close();
  expect_every_command_refuses(dir, db);
}

TEST(DamagedStore, UnreadableStoredProtocolIsRefusedNotRenamed) {
  ScratchDir dir;
  const std::string db = make_store(dir, 2);
  // The pages are sound; the stored protocol text of session 2 is not JSON any more.
  exec_sql(db, "UPDATE sessions SET protocol_json = substr(protocol_json, 1, 40) WHERE id = 2");
  const std::string out = (dir / "csv").string();
  for (const char* format : {"csv", "bids"}) {
    const auto r = run_palprig({"export", db, "--format", format, "--out", out});
    EXPECT_EQ(r.exit_code, 2) << format << ": " << r.out << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(db), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("session 2"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("protocol_json"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "csv" / "trials_long.csv"));
}

TEST(DamagedStore, StoredProtocolWithBrokenFingerNamesIsRefusedNotRenamed) {
  ScratchDir dir;
  const std::string db = make_store(dir, 1);
  exec_sql(db,
           "UPDATE sessions SET protocol_json = json_set(protocol_json, '$.fingers', json('[\"index\", 3]')) "
           "WHERE id = 1");
  const auto r = run_palprig({"export", db, "--out", (dir / "csv").string()});
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("fingers"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "csv" / "trials_long.csv"));
}

TEST(DamagedStore, SoundStoreStillExports) {
  ScratchDir dir;
  const std::string db = make_store(dir, 1);
  const auto r = run_palprig({"export", db, "--out", (dir / "csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = bytes_of((dir / "csv" / "trials_long.csv").string());
  EXPECT_NE(csv.find(",1,index,"), std::string::npos) << "the protocol's finger names were replaced";
  EXPECT_EQ(csv.find(",1,finger1,"), std::string::npos) << "the protocol's finger names were replaced";
}

}  // namespace
}  // namespace palprig
