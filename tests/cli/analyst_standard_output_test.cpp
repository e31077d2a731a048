// Standard output checked to the last byte (cli/standard_output.hpp), for the analyst's commands
// (this suite builds in the analyst-only build too): every command that prints, with its
// standard output on /dev/full, exits 1 with one line naming standard output and the system's
// reason (it exited 0 before, its results lost); on a pipe whose reader has gone it ends by
// SIGPIPE and says nothing, also when its parent left SIGPIPE ignored.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "store/sqlite_trial_store.hpp"
#include "study/protocol.hpp"
#include "study/session_plan.hpp"
#include "tests/support/analyst_store.hpp"
#include "tests/support/standard_output_support.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig;
using palprig::test_support::run_into_closed_pipe;
using palprig::test_support::run_to_dev_full;

namespace {

// The answers: exact on every trial but every fifth (all fingers).
std::filesystem::path store_every_fifth_answer_wrong(const std::filesystem::path& dir) {
  return palprig::testing::write_analyst_store(dir, [](int position) { return position % 5 == 0; });
}

}  // namespace

TEST(AnalystStandardOutput, AFailedWriteIsExitOneWithTheReasonForEveryCommand) {
  palprig::test_support::TempDir dir;
  const std::string db = store_every_fifth_answer_wrong(dir.path()).string();
  const auto csv = dir.write("times.csv", "mode,rt\na,1\na,2\na,3\nb,4\nb,5\nb,7\n");
  const std::string data = std::string(PALPRIG_SOURCE_DIR) + "/data";
  for (const std::string& args :
       {"stats trials " + db, "stats trials " + db + " --json", "stats trials " + db + " --format csv",
        std::string("stats proportion --k 6 --n 9"), "stats ttest " + csv.string() + " --column rt --by mode",
        "stats describe " + csv.string() + " --column rt", "export " + db + " --out " + (dir.path() / "csv").string(),
        "scene info " + data + "/scenes/phantom_abc.json", std::string("--help"), std::string("stats --help"),
        std::string("--version")}) {
    const auto r = run_to_dev_full(args);
    EXPECT_EQ(r.exit_code, 1) << args << ": " << r.err;
    EXPECT_EQ(palprig::testing::count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find("palprig: standard output: cannot write: No space left on device"), std::string::npos)
        << args << ": " << r.err;
  }
}

TEST(AnalystStandardOutput, AClosedPipeEndsQuietlyBySigpipe) {
  palprig::test_support::TempDir dir;
  const std::string db = store_every_fifth_answer_wrong(dir.path()).string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"stats", "trials", db}, std::vector<std::string>{"stats", "trials", db, "--json"},
        std::vector<std::string>{"stats", "proportion", "--k", "6", "--n", "9"}, std::vector<std::string>{"--help"}}) {
    const auto r = run_into_closed_pipe(args);
    EXPECT_TRUE(r.signalled) << args[0] << " " << args[1] << ": exit " << r.code << ", " << r.err;
    EXPECT_EQ(r.code, SIGPIPE) << args[0] << " " << args[1] << ": " << r.err;
    EXPECT_EQ(r.err, "") << args[0] << " " << args[1];
  }
}

TEST(AnalystStandardOutput, ARefusalKeepsItsExitCodeWhenNothingCouldBePrinted) {
  // Exit 2 and its own line: the refusal is the news, not the output that never came.
  const auto r = run_into_closed_pipe({"stats", "trials", "/nonexistent/store.db"});
  EXPECT_FALSE(r.signalled);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(palprig::testing::count_lines(r.err), 1) << r.err;
}
