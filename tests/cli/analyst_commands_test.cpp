// The analyst's commands (stats, export, store) on a store written through the study floor
// alone: no rig, no session, no controller. These suites build in the analyst-only build
// (-DPALPRIG_RIG=OFF) too (tests/CMakeLists.txt keeps analyst_*_test.cpp there), where the rig's
// commands are refused with one line and the palprig binary links no fieldbus library.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "store/sqlite_trial_store.hpp"
#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "tests/support/analyst_store.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::palprig_bin;
using palprig::test_support::run_process;

namespace {

// The answers: exact on every trial but the first (all fingers).
std::filesystem::path store_first_answer_wrong(const std::filesystem::path& dir) {
  return palprig::testing::write_analyst_store(dir, [](int position) { return position == 0; });
}

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(AnalystCommands, StatsTrialsReadsAStoreWrittenWithoutARig) {
  palprig::test_support::TempDir dir;
  const auto db = store_first_answer_wrong(dir.path());
  const auto r = run_process(palprig_bin() + " stats trials " + db.string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"ACC\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("three-finger"), std::string::npos) << r.out;  // a condition of paper 002
}

TEST(AnalystCommands, ExportWritesEveryTrialAsLongCsvAndBids) {
  palprig::test_support::TempDir dir;
  const auto db = store_first_answer_wrong(dir.path());
  const auto csv =
      run_process(palprig_bin() + " export " + db.string() + " --format csv --out " + (dir.path() / "csv").string());
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const std::string long_csv = slurp(dir.path() / "csv" / "trials_long.csv");
  // Paper 002's protocol: 3 fingers a trial, one row per finger value.
  const auto rows = std::count(long_csv.begin(), long_csv.end(), '\n');
  const Protocol p =
      load_protocol(std::filesystem::path(PALPRIG_SOURCE_DIR) / "data/protocols/discrimination_002.json");
  EXPECT_EQ(rows, 1 + 3 * static_cast<long>(make_session_plan(p, 1, 7).trials.size()));
  const auto bids =
      run_process(palprig_bin() + " export " + db.string() + " --format bids --out " + (dir.path() / "bids").string());
  ASSERT_EQ(bids.exit_code, 0) << bids.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "bids" / "dataset_description.json"));
}

TEST(AnalystCommands, StoreCopyKeepsEveryTrial) {
  palprig::test_support::TempDir dir;
  const auto db = store_first_answer_wrong(dir.path());
  const auto copy = dir.path() / "copy.db";
  const auto r = run_process(palprig_bin() + " store copy --from " + db.string() + " --to " + copy.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto a = run_process(palprig_bin() + " stats trials " + db.string() + " --json");
  const auto b = run_process(palprig_bin() + " stats trials " + copy.string() + " --json");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(a.out, b.out);
}

#ifdef PALPRIG_ANALYST_BUILD
TEST(AnalystCommands, RigCommandsAreRefusedWithOneLine) {
  for (const char* command : {"run", "demo", "experiment run --protocol x.json", "calibrate sweep", "gui"}) {
    const auto r = run_process(palprig_bin() + " " + command);
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find("-DPALPRIG_"), std::string::npos) << command << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(AnalystCommands, TheCommandLinksNoRigLibrary) {
  const auto r = run_process("ldd " + palprig_bin());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Qt6 Widgets is linked, on purpose: QCustomPlot, which draws the charts, is a QWidget
  // (charts/README.md). The rig's libraries are not.
  for (const char* lib : {"libmodbus", "libcomedi", "libevdev", "libevemu", "libOpenIGTLink"}) {
    EXPECT_EQ(r.out.find(lib), std::string::npos) << lib << " in\n" << r.out;
  }
}
#endif
