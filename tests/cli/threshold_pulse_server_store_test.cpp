// Threshold and pulse protocols keep their own SQLite tables; the PostgreSQL lab
// store holds discrimination/localisation trials only. A postgresql:// --db for them
// is a refused input (exit 2, names --db), and no local file named after the URI is created.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

TEST(experiments_server_store, threshold_and_pulse_protocols_refuse_a_postgresql_db) {
  for (const char* protocol : {"threshold_1up3down.json", "pulse_localisation_000.json"}) {
    const auto run =
        testing::run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / protocol).string(),
                              "--participant", "sim:1", "--db", "postgresql://palprig@127.0.0.1:1/palprig", "--quiet"});
    EXPECT_EQ(run.exit_code, 2) << protocol << ": " << run.err;
    EXPECT_NE(run.err.find("--db"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("not stored on the PostgreSQL lab server"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists("postgresql:")) << protocol << " made a file named after the URI";
  }
}

}  // namespace
}  // namespace palprig
