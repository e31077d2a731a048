// Readers run PRAGMA quick_check once per state of a database file and remember the sound ones
// in the user's cache (store/integrity_check_cache.hpp); writers check at every open. A file
// changed in any way since (here: garbage written into a page, with its modification time set
// back as `cp -p` or `touch -d` would) is a new state, checked again and refused.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>

#include "core/input_error.hpp"
#include "store/integrity_check_cache.hpp"
#include "store/sqlite_db.hpp"
#include "store/sqlite_trial_store.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

// The cache of this test only, in its scratch folder (the variable is the XDG one palprig reads).
class CacheHere {
 public:
  explicit CacheHere(const std::filesystem::path& dir) {
    const char* old = std::getenv("XDG_CACHE_HOME");
    if (old) old_ = old;
    had_ = old != nullptr;
    ::setenv("XDG_CACHE_HOME", dir.c_str(), 1);
  }
  ~CacheHere() {
    if (had_)
      ::setenv("XDG_CACHE_HOME", old_.c_str(), 1);
    else
      ::unsetenv("XDG_CACHE_HOME");
  }

 private:
  std::string old_;
  bool had_ = false;
};

std::filesystem::path make_store(const ScratchDir& dir) {
  auto db = dir / "trials.db";
  SqliteTrialStore store(db, TrialStore::Access::read_write);
  for (int i = 0; i < 50; ++i) store.enrol("p" + std::to_string(i), false);
  return db;
}

// File times are kept at the file system's granularity: a state is remembered once it is older
// than that (2 s, kSettledNs in integrity_check_cache.cpp).
void let_the_file_settle() { std::this_thread::sleep_for(std::chrono::milliseconds(2100)); }

Database::Check reader_check(const std::filesystem::path& db) {
  Database reader(db, Database::Mode::read_only);
  return reader.refuse_if_damaged();
}

TEST(IntegrityCheckCache, AReaderChecksEachFileStateOnceAWriterAlways) {
  ScratchDir dir;
  CacheHere cache(dir / "cache");
  const auto db = make_store(dir);
  EXPECT_EQ(reader_check(db), Database::Check::checked) << "a state too new to be told apart is not remembered";
  let_the_file_settle();
  EXPECT_EQ(reader_check(db), Database::Check::checked);
  EXPECT_EQ(reader_check(db), Database::Check::known_sound);
  EXPECT_TRUE(std::filesystem::exists(dir / "cache" / "palprig" / "sound-stores"));
  Database writer(db, Database::Mode::read_write_create);
  EXPECT_EQ(writer.refuse_if_damaged(), Database::Check::checked);
}

TEST(IntegrityCheckCache, AFileDamagedSinceItsCheckIsCheckedAgainAndRefused) {
  ScratchDir dir;
  CacheHere cache(dir / "cache");
  const auto db = make_store(dir);
  let_the_file_settle();
  ASSERT_EQ(reader_check(db), Database::Check::checked);
  ASSERT_EQ(reader_check(db), Database::Check::known_sound);

  struct stat before {};
  ASSERT_EQ(::stat(db.c_str(), &before), 0);
  {
    // Page 2 (the first table's root) overwritten in place: the size stays.
    std::mt19937 random(11);
    std::string garbage(4096, '\0');
    for (char& c : garbage) c = static_cast<char>(random() & 0xff);
    std::fstream f(db, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(4096);
    f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  }
  // The modification time set back as it was: only the status-change time tells.
  const timespec times[2] = {before.st_atim, before.st_mtim};
  ASSERT_EQ(::utimensat(AT_FDCWD, db.c_str(), times, 0), 0);
  ASSERT_EQ(std::filesystem::file_size(db), static_cast<std::uintmax_t>(before.st_size));
  let_the_file_settle();
  EXPECT_THROW(reader_check(db), InputError);
}

TEST(IntegrityCheckCache, WithoutACacheFolderEveryReaderChecks) {
  ScratchDir dir;
  std::ofstream(dir / "not-a-folder") << "x";
  CacheHere cache(dir / "not-a-folder");
  const auto db = make_store(dir);
  let_the_file_settle();
  EXPECT_EQ(reader_check(db), Database::Check::checked);
  EXPECT_EQ(reader_check(db), Database::Check::checked);
}

}  // namespace
}  // namespace palprig
