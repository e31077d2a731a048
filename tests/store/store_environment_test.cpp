// The machine, not the data, keeps a trial database from being written: a read-only folder, a
// read-only file, a disk that fills (a file that may not grow: RLIMIT_FSIZE in the child, with
// SIGXFSZ ignored, as /dev/full or a tiny tmpfs are not available here). Each is one line of
// palprig's own naming the file and the cause, not SQLite's raw text; exit 2 where nothing was
// written, and what was committed before a full disk stays readable.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_and_paths.hpp"

using palprig::test_support::palprig_bin;
using palprig::test_support::read_file;
using palprig::test_support::run_process;
using palprig::test_support::TempDir;

namespace {

// Root writes through permission bits: the child then runs as nobody (setpriv), so a folder or
// file it does not own and may not write is what a user meets.

std::string session(const std::filesystem::path& db) {
  return palprig_bin() + " experiment run --protocol " + palprig::testing::discrimination_protocol_file() +
         " --participant sim:3 --quiet --db " + db.string();
}

int line_count(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

struct Result {
  int exit_code = -1;
  std::string err;
};

// palprig in a child whose files may not grow beyond `max_bytes` (SIGXFSZ ignored, so a write
// past it fails with EFBIG as on a full disk).
Result run_with_file_size_limit(const std::vector<std::string>& args, rlim_t max_bytes,
                                const std::filesystem::path& dir) {
  const auto err_file = dir / "stderr";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);  // before the limit bites
    ::dup2(fd, 2);
    const int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, 0);
    ::dup2(null, 1);
    ::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{max_bytes, max_bytes};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::vector<char*> argv;
    std::string bin = palprig_bin();
    argv.push_back(bin.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(bin.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), read_file(err_file)};
}

}  // namespace

TEST(StoreEnvironment, AReadOnlyFolderIsOneLineExitTwoAndNothingIsWritten) {
  TempDir dir;
  const auto folder = dir.path() / "locked";
  std::filesystem::create_directory(folder);
  ::chmod(folder.c_str(), 0555);
  const auto db = folder / "trials.db";
  const auto r = run_process(palprig::testing::as_unprivileged() + session(db));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err, "palprig: " + db.string() + ": file: a trial database palprig can open and write (its folder " +
                       folder.string() + " is read-only; nothing was written)\n");
  EXPECT_FALSE(std::filesystem::exists(db));
  ::chmod(folder.c_str(), 0755);
}

TEST(StoreEnvironment, AReadOnlyFileIsOneLineExitTwoAndKeptAsItWas) {
  TempDir dir;
  ::chmod(dir.path().c_str(), 0777);  // the folder may be written (-wal, -shm), the file not
  const auto db = dir.path() / "trials.db";
  ASSERT_EQ(run_process(session(db)).exit_code, 0);
  ::chmod(db.c_str(), 0444);
  const std::string before = read_file(db);
  const auto r = run_process(palprig::testing::as_unprivileged() + palprig_bin() + " experiment run --protocol " +
                             palprig::testing::discrimination_protocol_file() + " --participant sim:4 --quiet --db " +
                             db.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err,
            "palprig: " + db.string() +
                ": file: a trial database palprig can open and write (the file is read-only; nothing was written)\n");
  EXPECT_EQ(read_file(db), before);
  // Readers still read it.
  EXPECT_EQ(run_process(palprig::testing::as_unprivileged() + palprig_bin() + " stats trials " + db.string()).exit_code,
            0);
}

TEST(StoreEnvironment, AFullDiskIsOneLineOfPalprigsOwnAndKeepsWhatWasCommitted) {
  TempDir dir;
  const std::vector<std::string> args = {
      "experiment",    "run",   "--protocol", palprig::testing::discrimination_protocol_file(),
      "--participant", "sim:5", "--quiet",    "--db"};
  // Too small for the empty store: nothing was written, exit 2.
  {
    auto a = args;
    a.push_back((dir.path() / "tiny.db").string());
    const Result r = run_with_file_size_limit(a, 2048, dir.path());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("palprig: " + (dir.path() / "tiny.db").string() +
                              ": file: a trial database palprig can open and write (",
                          0),
              0u)
        << r.err;
    EXPECT_NE(r.err.find("the disk "), std::string::npos) << r.err;
  }
  // Room for the store and some trials: the disk fills during the session. The line is
  // palprig's, naming the file and the cause; the trials committed before it are all there.
  auto a = args;
  const auto db = dir.path() / "full.db";
  a.push_back(db.string());
  const Result r = run_with_file_size_limit(a, rlim_t{160} * 1024, dir.path());
  EXPECT_NE(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("database or disk is full\n"), std::string::npos) << r.err;  // not SQLite's text alone
  EXPECT_NE(r.err.find("palprig: " + db.string() + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the disk "), std::string::npos) << r.err;  // "is full" or "may be full", by SQLite's code
  const auto check =
      run_process("sqlite3 " + db.string() + " 'PRAGMA integrity_check; SELECT count(*) > 0 FROM trials'");
  if (check.exit_code == 0) {
    EXPECT_EQ(check.out, "ok\n1\n");
  }
}
