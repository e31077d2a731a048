// Standard output checked to the last byte (cli/standard_output.hpp) for the rig's commands: on
// /dev/full they exit 1 with one line (their results were lost behind exit 0 before); and a
// reader that goes away never kills a session mid-run: `experiment run | head -1` used to die of
// SIGPIPE at its first line with the session unfinished; now the session runs to its end, every
// trial stored and every channel vented, and only then does the process end by SIGPIPE.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "store/sqlite_trial_store.hpp"
#include "tests/support/standard_output_support.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig;
using palprig::test_support::run_into_closed_pipe;
using palprig::test_support::run_to_dev_full;

namespace {}  // namespace

TEST(StandardOutput, TheRigsCommandsExitOneWhenTheirOutputCannotBeWritten) {
  palprig::test_support::TempDir dir;
  for (const std::string& args :
       {"experiment plan --protocol " + palprig::testing::shipped_data("protocols/discrimination_002.json") +
            " --participant P01",
        "check " + palprig::testing::shipped_data("rigs/simulated.json") + " " +
            palprig::testing::shipped_data("scenes/phantom_abc.json"),
        std::string("demo"),
        "experiment run --protocol " + palprig::testing::shipped_data("protocols/discrimination_002.json") +
            " --participant sim:1 --db " + (dir.path() / "s.db").string() + " --quiet"}) {
    const auto r = run_to_dev_full(args);
    EXPECT_EQ(r.exit_code, 1) << args << ": " << r.err;
    // The one line, last (plan's note on the participant number comes before it).
    const std::string line = "palprig: standard output: cannot write: No space left on device\n";
    EXPECT_TRUE(r.err.size() >= line.size() && r.err.compare(r.err.size() - line.size(), line.size(), line) == 0)
        << args << ": " << r.err;
    EXPECT_LE(palprig::testing::count_lines(r.err), 2) << args << ": " << r.err;
  }
}

TEST(StandardOutput, AReaderThatGoesAwayNeverStopsASessionMidRun) {
  for (bool parent_ignores_sigpipe : {false, true}) {
    palprig::test_support::TempDir dir;
    const auto db = dir.path() / "s.db";
    const auto r = run_into_closed_pipe(
        {"experiment", "run", "--protocol", palprig::testing::shipped_data("protocols/discrimination_002.json"),
         "--participant", "sim:1", "--db", db.string()},
        parent_ignores_sigpipe);
    EXPECT_TRUE(r.signalled) << "exit " << r.code << ": " << r.err;
    EXPECT_EQ(r.code, SIGPIPE) << r.err;
    EXPECT_EQ(r.err, "");
    SqliteTrialStore store(db, TrialStore::Access::read_only);
    const auto sessions = store.list_sessions();
    ASSERT_EQ(sessions.size(), 1u);
    EXPECT_EQ(sessions[0].status, "completed") << "parent ignores SIGPIPE: " << parent_ignores_sigpipe;
    EXPECT_EQ(store.read_trials(true).size(), 32u);
  }
}
