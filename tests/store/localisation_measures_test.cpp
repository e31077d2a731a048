// Localisation has no true negatives (every tumor-free spot of the tissue would be one), so its
// Sp and ACC have no denominator: n/a in text, null in JSON, NA in CSV; never 0.000 [0, 0.1].
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::run_palprig;
using testing::ScratchDir;

TEST(LocalisationMeasures, SpecificityAndAccuracyAreNotApplicable) {
  ScratchDir dir;
  const std::string db = (dir / "loc.db").string();
  const auto run =
      run_palprig({"experiment", "run", "--protocol", (testing::protocols_dir() / "localisation_002.json").string(),
                   "--participant", "sim:4", "--db", db, "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;

  const auto json = run_palprig({"stats", "trials", db, "--json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto rows = nlohmann::json::parse(json.out)["rows"];
  ASSERT_FALSE(rows.empty());
  for (const auto& row : rows) {
    EXPECT_TRUE(row["Sp"].is_null()) << row.dump();
    EXPECT_TRUE(row["ACC"].is_null()) << row.dump();
    EXPECT_TRUE(row["TN"].is_null()) << row.dump();
    EXPECT_TRUE(row["Se"].is_object()) << row.dump();  // tumors found of tumors present: defined
  }

  const auto text = run_palprig({"stats", "trials", db});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("n/a"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("0.000 [0.000"), std::string::npos) << text.out;

  const auto csv = run_palprig({"stats", "trials", db, "--format", "csv"});
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_NE(csv.out.find(",NA,NA,NA"), std::string::npos) << csv.out;
}

}  // namespace
}  // namespace palprig
