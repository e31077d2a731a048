// `palprig export` of a store holding every task kind: each shipped protocol run by
// simulated participants, exported as long CSV and BIDS with every trial, plotted per kind;
// an empty store, a full disk (/dev/full and a full tmpfs) and an unwritable folder are errors
// that leave no file looking complete. The official bids-validator checks the BIDS tree when
// `make test` could install it (npm), and says why it skipped otherwise.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "store/sqlite_trial_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/support.hpp"
#include "tests/support/text_and_paths.hpp"

namespace palprig {
namespace {

namespace fs = std::filesystem;
using testing::run_palprig;
using testing::ScratchDir;

const std::vector<std::string> kProtocols = {
    "discrimination_002.json", "discrimination_002_confidence.json", "localisation_002.json", "threshold_1up3down.json",
    "threshold_quest.json",    "pulse_localisation_000.json",        "pulse_generated.json"};
const std::vector<std::string> kParticipants = {"sim:1", "sim:2"};

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);) out.push_back(line);
  return out;
}

std::int64_t store_scalar(const fs::path& db, const std::string& sql) {
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
  auto q = store.database().prepare(sql);
  return q.step() ? q.integer(0) : -1;
}

// One store, every shipped protocol, two simulated participants. ctest runs each case in its own
// process, and the 14 sessions took minutes per case under the sanitizers: the store is made
// once per palprig binary (the first case to come makes it under a lock, the others wait and
// copy it), beside the binary in test-cache/.
class ExportEveryTask : public ::testing::Test {
 protected:
  // A failure here fails every case (SetUp), never skips it: gtest skips the cases of a suite
  // whose SetUpTestSuite failed fatally, and ctest would count that as skipped, not failed.
  static void SetUpTestSuite() {
    try {
      make_store();
    } catch (const std::exception& e) {
      setup_error_ = e.what();
    }
  }
  void SetUp() override {
    if (!setup_error_.empty()) FAIL() << "the store of every task kind: " << setup_error_;
  }
  static void make_store() {
    dir_ = fs::temp_directory_path() / ("palprig-export-every-task-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    db_ = dir_ / "every_task.db";
    const fs::path bin = PALPRIG_BIN;
    const fs::path cache = bin.parent_path() / "test-cache";
    fs::create_directories(cache);
    const std::string stamp =
        std::to_string(fs::last_write_time(bin).time_since_epoch().count()) + "-" + std::to_string(fs::file_size(bin));
    const fs::path cached_db = cache / ("every_task-" + stamp + ".db");
    const fs::path cached_runs = cache / ("every_task-" + stamp + ".json");
    const int lock = ::open((cache / "every_task.lock").c_str(), O_CREAT | O_RDWR, 0644);
    if (lock < 0 || ::flock(lock, LOCK_EX) != 0)
      throw std::runtime_error("cannot lock " + (cache / "every_task.lock").string());
    struct Unlock {
      int fd;
      ~Unlock() { ::close(fd); }  // closing releases the lock
    } unlock{lock};
    if (!fs::exists(cached_runs)) {
      const fs::path making = cache / ("every_task-" + stamp + ".making.db");
      fs::remove(making);
      nlohmann::json printed = nlohmann::json::object();
      for (const std::string& participant : kParticipants) {
        for (const std::string& protocol : kProtocols) {
          const auto r = run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / protocol).string(),
                                      "--participant", participant, "--db", making.string()});
          std::string run = protocol;
          run.append(" ").append(participant);
          if (r.exit_code != 0) throw std::runtime_error(run + ": exit " + std::to_string(r.exit_code) + ": " + r.err);
          printed[run] = r.out;
        }
      }
      fs::rename(making, cached_db);
      std::ofstream out(cached_runs);
      out << printed.dump();  // written last: its presence says the store is whole
      if (!out.flush()) throw std::runtime_error("cannot write " + cached_runs.string());
    }
    fs::copy_file(cached_db, db_);
    const nlohmann::json printed = nlohmann::json::parse(file_text(cached_runs));
    for (auto it = printed.begin(); it != printed.end(); ++it) runs_[it.key()] = it.value().get<std::string>();
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static fs::path dir_, db_;
  static std::map<std::string, std::string> runs_;
  static std::string setup_error_;
};
std::string ExportEveryTask::setup_error_;
fs::path ExportEveryTask::dir_, ExportEveryTask::db_;
std::map<std::string, std::string> ExportEveryTask::runs_;

TEST_F(ExportEveryTask, LongCsvHoldsEveryTrialOfEveryKind) {
  const fs::path out = dir_ / "csv";
  const auto r = run_palprig({"export", db_.string(), "--format", "csv", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::int64_t threshold = store_scalar(db_, "SELECT count(*) FROM threshold_trials");
  const std::int64_t pulse = store_scalar(db_, "SELECT count(*) FROM pulse_trials");
  const std::int64_t other = store_scalar(db_, "SELECT count(*) FROM trials");
  ASSERT_GT(threshold, 0);
  ASSERT_GT(pulse, 0);
  EXPECT_NE(r.out.find(std::to_string(threshold + pulse + other) + " trials (" + std::to_string(other) +
                       " discrimination/localisation, " + std::to_string(threshold) + " threshold, " +
                       std::to_string(pulse) + " pulse)"),
            std::string::npos)
      << r.out;

  const auto threshold_lines = lines_of(file_text(out / "threshold_trials.csv"));
  ASSERT_EQ(static_cast<std::int64_t>(threshold_lines.size()), threshold + 1);
  const auto header = palprig::testing::split_cells(threshold_lines[0], ',');
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<std::size_t>(it - header.begin());
  };
  // The track's estimate after its last trial is the threshold the session printed at its end.
  std::map<std::string, std::string> last_estimate;  // "participant track_name" -> estimate
  for (std::size_t i = 1; i < threshold_lines.size(); ++i) {
    const auto cells = palprig::testing::split_cells(threshold_lines[i], ',');
    ASSERT_EQ(cells.size(), header.size()) << threshold_lines[i];
    if (cells[column("protocol")].rfind("threshold_1up3down", 0) != 0) continue;
    last_estimate[cells[column("participant")] + " " + cells[column("track_name")]] = cells[column("estimate_kPa")];
  }
  ASSERT_FALSE(last_estimate.empty());
  for (const std::string& participant : kParticipants) {
    const std::string printed = runs_["threshold_1up3down.json " + participant];
    const std::regex line("(\\S+): threshold ([0-9.]+) kPa");
    int matched = 0;
    for (auto it = std::sregex_iterator(printed.begin(), printed.end(), line); it != std::sregex_iterator(); ++it) {
      const std::string key = participant + " " + (*it)[1].str();
      ASSERT_TRUE(last_estimate.count(key)) << key;
      EXPECT_NEAR(std::stod(last_estimate[key]), std::stod((*it)[2].str()), 0.0006) << key;
      ++matched;
    }
    EXPECT_EQ(matched, 2) << printed;
  }

  const auto pulse_lines = lines_of(file_text(out / "pulse_trials.csv"));
  ASSERT_EQ(static_cast<std::int64_t>(pulse_lines.size()), pulse + 1);
  const auto pulse_header = palprig::testing::split_cells(pulse_lines[0], ',');
  for (const char* name : {"mark_x_mm", "distance_mm", "hit", "hit_radius_mm", "artery"}) {
    EXPECT_NE(std::find(pulse_header.begin(), pulse_header.end(), name), pulse_header.end()) << name;
  }
  for (std::size_t i = 1; i < pulse_lines.size(); ++i)
    EXPECT_EQ(palprig::testing::split_cells(pulse_lines[i], ',').size(), pulse_header.size());
  EXPECT_TRUE(fs::exists(out / "trials_long.csv"));
  EXPECT_TRUE(fs::exists(out / "marks.csv"));
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    EXPECT_EQ(e.path().extension(), ".csv") << e.path() << ": no partial file is left";
  }
}

TEST_F(ExportEveryTask, BidsHasARunPerSessionWithEveryTrialAndEveryColumnDescribed) {
  const fs::path out = dir_ / "bids";
  const auto r =
      run_palprig({"export", db_.string(), "--format", "bids", "--out", out.string(), "--author", "A. Tester"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto description = nlohmann::json::parse(file_text(out / "dataset_description.json"));
  EXPECT_EQ(description["Authors"], nlohmann::json::array({"A. Tester"}));
  EXPECT_TRUE(fs::exists(out / "README"));
  std::int64_t rows = 0;
  int runs = 0;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    if (name.size() < 8 || name.substr(name.size() - 8) != "_beh.tsv") continue;
    ++runs;
    const auto lines = lines_of(file_text(e.path()));
    ASSERT_GE(lines.size(), 2u) << e.path();
    rows += static_cast<std::int64_t>(lines.size()) - 1;
    const auto header = palprig::testing::split_cells(lines[0], '\t');
    for (const auto& line : lines)
      EXPECT_EQ(palprig::testing::split_cells(line, '\t').size(), header.size()) << e.path() << ": " << line;
    fs::path sidecar = e.path();
    sidecar.replace_extension(".json");
    const auto side = nlohmann::json::parse(file_text(sidecar));
    for (const std::string& column : header) EXPECT_TRUE(side.contains(column)) << sidecar << " describes " << column;
  }
  EXPECT_EQ(runs, store_scalar(db_, "SELECT count(*) FROM sessions"));
  EXPECT_EQ(rows, store_scalar(db_,
                               "SELECT (SELECT count(*) FROM trials) + (SELECT count(*) FROM threshold_trials) + "
                               "(SELECT count(*) FROM pulse_trials)"));
  const std::string participants = file_text(out / "participants.tsv");
  EXPECT_EQ(lines_of(participants).size(), kParticipants.size() + 1) << participants;
}

fs::path bids_validator() {
  if (const char* env = std::getenv("PALPRIG_BIDS_VALIDATOR")) return env;
  return PALPRIG_BIDS_VALIDATOR;
}

TEST_F(ExportEveryTask, OfficialBidsValidatorReportsNoErrorAndNoWarning) {
  const fs::path validator = bids_validator();
  if (!fs::exists(validator)) {
    GTEST_SKIP() << "bids-validator is not at " << validator
                 << " (make test installs it with npm into the build folder; npm was not available)";
  }
  const fs::path out = dir_ / "bids_validated";
  // Two authors: with one, the validator warns TOO_FEW_AUTHORS ("ignore if all contributors are
  // listed"), which a single-author lab may do.
  const auto r = run_palprig({"export", db_.string(), "--format", "bids", "--out", out.string(), "--author",
                              "A. Tester", "--author", "B. Tester"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto v = test_support::run_process(validator.string() + " --json " + out.string());
  const auto report = nlohmann::json::parse(v.out, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << v.out << v.err;
  EXPECT_EQ(report["issues"]["errors"].size(), 0u) << report["issues"]["errors"].dump(2);
  EXPECT_EQ(report["issues"]["warnings"].size(), 0u) << report["issues"]["warnings"].dump(2);
  EXPECT_EQ(v.exit_code, 0) << v.err;
}

TEST_F(ExportEveryTask, PlotDrawsEveryKindAsPngAndSvg) {
  const fs::path plots = dir_ / "plots";
  const auto r = run_palprig(
      {"export", db_.string(), "--out", (dir_ / "csv_for_plots").string(), "--plot", plots.string(), "--svg"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* stem : {"measures_by_condition", "pulse_hits_by_condition", "psychometric_one_finger"}) {
    EXPECT_GT(fs::file_size(plots / (std::string(stem) + ".png")), 2000u) << stem;
    EXPECT_NE(file_text(plots / (std::string(stem) + ".svg")).find("<svg"), std::string::npos) << stem;
  }
  int tracks = 0;
  for (const auto& e : fs::directory_iterator(plots))
    tracks += e.path().filename().string().rfind("track_session", 0) == 0;
  EXPECT_EQ(tracks, 2 * 2 * 2) << "a PNG and an SVG per threshold session";
}

TEST(ExportRefusals, AStoreWithoutTrialsIsAnErrorNotAnEmptyExport) {
  ScratchDir dir;
  const fs::path db = dir / "empty.db";
  { const auto store = open_trial_store(db.string(), TrialStore::Access::read_write); }
  for (const char* format : {"csv", "bids"}) {
    const auto r = run_palprig({"export", db.string(), "--format", format, "--out", (dir / format).string()});
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(db.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("holds none"), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("0 trials"), std::string::npos) << r.out;
    EXPECT_TRUE(!fs::exists(dir / format) || fs::is_empty(dir / format)) << "nothing written";
  }
}

std::string one_session(const fs::path& db) {
  const auto r =
      run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "discrimination_002.json").string(),
                   "--participant", "sim:9", "--db", db.string(), "--quiet"});
  return r.exit_code == 0 ? "" : r.err;
}

TEST(ExportRefusals, AFullDiskIsExitOneAndLeavesNoFileThatLooksComplete) {
  ScratchDir dir;
  const fs::path db = dir / "trials.db";
  ASSERT_EQ(one_session(db), "");
  // /dev/full: the file is a link to it (a device is written directly; every write fails with ENOSPC).
  const fs::path out = dir / "devfull";
  fs::create_directories(out);
  fs::create_symlink("/dev/full", out / "trials_long.csv");
  auto r = run_palprig({"export", db.string(), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find((out / "trials_long.csv").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("trials from"), std::string::npos) << "no success line: " << r.out;
  EXPECT_FALSE(fs::exists(out / "marks.csv")) << "the export stopped at the failed file";
  ASSERT_TRUE(fs::is_character_file("/dev/full")) << "the device itself is untouched";

  // A filesystem that fills up half-way (root only: CI's tests run as root).
  const fs::path small = dir / "small";
  fs::create_directories(small);
  if (::geteuid() != 0 || ::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=8k") != 0) {
    GTEST_SKIP() << "cannot mount a small tmpfs here (not root, or mount refused): the /dev/full case ran";
  }
  for (const char* format : {"csv", "bids"}) {
    r = run_palprig({"export", db.string(), "--format", format, "--out", (small / format).string()});
    EXPECT_EQ(r.exit_code, 1) << format << ": " << r.out << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    for (const auto& e : fs::recursive_directory_iterator(small / format)) {
      EXPECT_NE(e.path().extension(), ".partial") << e.path() << ": no temporary is left";
    }
  }
  EXPECT_FALSE(fs::exists(small / "csv" / "trials_long.csv")) << "the long file does not fit in 8 KiB";
  ::umount(small.c_str());
}

TEST(ExportRefusals, AnUnwritableFolderIsOneLineNamingTheFile) {
  ScratchDir dir;
  const fs::path db = dir / "trials.db";
  ASSERT_EQ(one_session(db), "");
  const fs::path out = dir / "readonly";
  fs::create_directories(out);
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read | fs::perms::group_exec |
                           fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(dir.path(), fs::perms::all);
  const std::string as_nobody = ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
  const auto r =
      test_support::run_process(as_nobody + PALPRIG_BIN + " export " + db.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find((out / "trials_long.csv").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Permission denied"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(out));
}

}  // namespace
}  // namespace palprig
