// Every writer checks every write and its close (io/checked_output.hpp): on /dev/full, on a
// full file system (a filled 64 KiB tmpfs) and in a folder it may not write, `telemetry to-csv`,
// `scene render`, `scene generate`, `stats psychometric --plot`, `calibrate sweep` and `store
// copy` fail with one line naming the file and the system's reason, exit 1 (store copy: its
// store's convention, see there), and leave no file that looks complete. Before, they said "wrote N records" and exited
// 0 over an empty or short file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/full_filesystem.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

using test_support::FullFilesystem;
using test_support::palprig_bin;
using test_support::ProcessResult;
using test_support::run_process;
using test_support::TempDir;

std::string source(const std::string& relative) { return test_support::source_dir() + "/" + relative; }

// Root writes through permission bits: the child runs as nobody for the read-only folder.
std::string as_unprivileged() { return ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : ""; }

int line_count(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

// One line, exit 1, naming the file and the reason; and a device stays the device (a writer
// that tidied up after itself by removing its path once took /dev/full away from the machine).
void expect_failed_write(const ProcessResult& r, const std::string& file, const std::string& reason) {
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full")) << "/dev/full was replaced or removed";
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("wrote"), std::string::npos) << "claimed a write: " << r.out;
}

// A folder nobody may write (mode 0555, owned by root).
std::filesystem::path read_only_folder(const TempDir& dir) {
  auto folder = dir.path() / "read-only";
  std::filesystem::create_directory(folder);
  ::chmod(dir.path().c_str(), 0755);
  ::chmod(folder.c_str(), 0555);
  return folder;
}

#define SKIP_UNLESS_MOUNTED(fs) \
  if (!(fs).mounted()) GTEST_SKIP() << (fs).reason()

// The writers, each as a command line writing `out`.
std::string telemetry_to_csv(const std::filesystem::path& bin, const std::filesystem::path& out) {
  return palprig_bin() + " telemetry to-csv " + bin.string() + " " + out.string();
}
std::string scene_render(const std::filesystem::path& out) {
  return palprig_bin() + " scene render " + source("data/scenes/phantom_abc.json") + " --out " + out.string();
}
std::string scene_generate(const std::filesystem::path& out) {
  return palprig_bin() + " scene generate --seed 7 --out " + out.string();
}

std::filesystem::path telemetry_bin(const TempDir& dir) {
  auto bin = dir.path() / "run.bin";
  const auto r = run_process(palprig_bin() + " run --scene " + source("data/scenes/phantom_abc.json") +
                             " --input sweep --duration-s 0.5 --telemetry " + bin.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ::chmod(bin.c_str(), 0644);
  return bin;
}

TEST(WritersCheckWrites, TelemetryToCsv) {
  TempDir dir;
  const auto bin = telemetry_bin(dir);
  expect_failed_write(run_process(telemetry_to_csv(bin, "/dev/full")), "/dev/full", "No space left on device");

  const auto ro = read_only_folder(dir);
  expect_failed_write(run_process(as_unprivileged() + telemetry_to_csv(bin, ro / "run.csv")), (ro / "run.csv").string(),
                      "Permission denied");
  EXPECT_TRUE(std::filesystem::is_empty(ro));

  FullFilesystem full(dir.path() / "full");
  SKIP_UNLESS_MOUNTED(full);
  expect_failed_write(run_process(telemetry_to_csv(bin, full.folder() / "run.csv")),
                      (full.folder() / "run.csv").string(), "No space left on device");
  EXPECT_TRUE(full.left_behind().empty()) << *full.left_behind().begin();
}

TEST(WritersCheckWrites, ATruncatedTelemetryFileLeavesNoCsv) {
  TempDir dir;
  const auto bin = telemetry_bin(dir);
  std::filesystem::resize_file(bin, std::filesystem::file_size(bin) - 7);
  const auto r = run_process(telemetry_to_csv(bin, dir.path() / "run.csv"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "run.csv")) << "a CSV of the records before the cut looks complete";
}

TEST(WritersCheckWrites, SceneRender) {
  TempDir dir;
  // /dev/full has no .pgm or .csv name (render would refuse it before writing): a link with one.
  std::filesystem::create_symlink("/dev/full", dir.path() / "full.csv");
  expect_failed_write(run_process(scene_render(dir.path() / "full.csv")), (dir.path() / "full.csv").string(),
                      "No space left on device");

  const auto ro = read_only_folder(dir);
  expect_failed_write(run_process(as_unprivileged() + scene_render(ro / "map.pgm")), (ro / "map.pgm").string(),
                      "Permission denied");
  EXPECT_TRUE(std::filesystem::is_empty(ro));

  FullFilesystem full(dir.path() / "full");
  SKIP_UNLESS_MOUNTED(full);
  expect_failed_write(run_process(scene_render(full.folder() / "map.csv")), (full.folder() / "map.csv").string(),
                      "No space left on device");
  EXPECT_TRUE(full.left_behind().empty());
}

TEST(WritersCheckWrites, SceneGenerate) {
  TempDir dir;
  expect_failed_write(run_process(scene_generate("/dev/full")), "/dev/full", "No space left on device");

  const auto ro = read_only_folder(dir);
  expect_failed_write(run_process(as_unprivileged() + scene_generate(ro / "case.json")), (ro / "case.json").string(),
                      "Permission denied");
  EXPECT_TRUE(std::filesystem::is_empty(ro));

  FullFilesystem full(dir.path() / "full");
  SKIP_UNLESS_MOUNTED(full);
  expect_failed_write(run_process(scene_generate(full.folder() / "case.json")), (full.folder() / "case.json").string(),
                      "No space left on device");
  EXPECT_TRUE(full.left_behind().empty());

  // And where there is room, the file is whole and replaces the old one.
  const auto ok = run_process(scene_generate(dir.path() / "case.json"));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(run_process(palprig_bin() + " scene info " + (dir.path() / "case.json").string()).exit_code, 0);
}

TEST(WritersCheckWrites, StatsPsychometricPlot) {
  TempDir dir;
  {
    std::ofstream csv(dir.path() / "levels.csv");
    csv << "stimulus,yes,n\n1,2,20\n1.5,5,20\n2,10,20\n2.5,15,20\n3,19,20\n";
  }
  ::chmod((dir.path() / "levels.csv").c_str(), 0644);
  const std::string fit = palprig_bin() + " stats psychometric " + (dir.path() / "levels.csv").string() +
                          " --level stimulus --response yes --n n --bootstrap 0 --plot ";

  const auto ro = read_only_folder(dir);
  const auto r = run_process(as_unprivileged() + fit + ro.string());
  expect_failed_write(r, (ro / "psychometric_all.png").string().substr(0, ro.string().size()), "Permission denied");
  EXPECT_TRUE(std::filesystem::is_empty(ro));

  FullFilesystem full(dir.path() / "full");
  SKIP_UNLESS_MOUNTED(full);
  expect_failed_write(run_process(fit + full.folder().string()), full.folder().string(), "No space left on device");
  EXPECT_TRUE(full.left_behind().empty()) << *full.left_behind().begin();
}

// A store is not written through the file writer but by SQLite, one transaction per session:
// a device is refused (exit 2: SQLite cannot keep a store there), and a copy that cannot create
// its new target is refused with palprig's line (exit 2, nothing written), the new file removed.
TEST(WritersCheckWrites, StoreCopy) {
  TempDir dir;
  const auto db = dir.path() / "study.db";
  const auto made =
      run_process(palprig_bin() + " experiment run --protocol " + source("data/protocols/discrimination_002.json") +
                  " --participant sim:2 --quiet --db " + db.string());
  ASSERT_EQ(made.exit_code, 0) << made.err;
  ::chmod(db.c_str(), 0644);
  const std::string copy = palprig_bin() + " store copy --from " + db.string() + " --to ";

  const auto dev = run_process(copy + "/dev/full");
  EXPECT_EQ(dev.exit_code, 2) << dev.err;
  EXPECT_EQ(line_count(dev.err), 1) << dev.err;
  EXPECT_NE(dev.err.find("/dev/full: file: a trial database: a regular file or a new path"), std::string::npos)
      << dev.err;
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full"));

  const auto ro = read_only_folder(dir);
  const auto denied = run_process(as_unprivileged() + copy + (ro / "copy.db").string());
  EXPECT_EQ(denied.exit_code, 2) << denied.err;
  EXPECT_EQ(line_count(denied.err), 1) << denied.err;
  EXPECT_NE(denied.err.find((ro / "copy.db").string()), std::string::npos) << denied.err;
  EXPECT_NE(denied.err.find("read-only"), std::string::npos) << denied.err;
  EXPECT_TRUE(std::filesystem::is_empty(ro));

  FullFilesystem full(dir.path() / "full");
  SKIP_UNLESS_MOUNTED(full);
  const auto target = full.folder() / "copy.db";
  const auto r = run_process(copy + target.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(target.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the disk"), std::string::npos) << r.err;
  EXPECT_TRUE(full.left_behind().empty()) << *full.left_behind().begin();
}

// The sweep file is streamed hold by hold (a stopped sweep keeps its holds), each flush and the
// close checked; a file that failed before any hold is removed (one that failed later is
// renamed NAME.partial, which the line names).
TEST(WritersCheckWrites, CalibrateSweep) {
  TempDir dir;
  const std::string sweep = palprig_bin() +
                            " calibrate sweep --channels 1 --from-kPa 10 --to-kPa 20 --step-kPa 10 "
                            "--repeats 1 --out ";
  expect_failed_write(run_process(sweep + "/dev/full"), "/dev/full", "No space left on device");

  const auto ro = read_only_folder(dir);
  expect_failed_write(run_process(as_unprivileged() + sweep + (ro / "sweep.csv").string()), (ro / "sweep.csv").string(),
                      "Permission denied");
  EXPECT_TRUE(std::filesystem::is_empty(ro));

  FullFilesystem full(dir.path() / "full");
  SKIP_UNLESS_MOUNTED(full);
  expect_failed_write(run_process(sweep + (full.folder() / "sweep.csv").string()),
                      (full.folder() / "sweep.csv").string(), "No space left on device");
  EXPECT_TRUE(full.left_behind().empty()) << *full.left_behind().begin();
}

}  // namespace
}  // namespace palprig
