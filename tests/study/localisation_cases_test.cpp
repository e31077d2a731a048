// Localisation protocols over a set of cases, a generated case per trial, and normal cases
// (study/protocol.hpp, study/localisation_case.hpp). Each of these was refused or impossible:
// a normal case could not be named ("a scene that lists its tumors' outlines ... has none"),
// and a protocol took exactly one scene.
#include "study/localisation_case.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "formats/function_scene_file.hpp"
#include "study/scoring.hpp"
#include "study/session_plan.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

// The first hard seed whose case holds no tumor (about one in four).
std::uint64_t normal_hard_seed() {
  for (std::uint64_t seed = 1;; ++seed) {
    if (generate_case(seed, CaseDifficulty::hard).tumors.empty()) return seed;
  }
}

nlohmann::json localisation(const nlohmann::json& what) {
  nlohmann::json p = {{"version", 1},
                      {"name", "cases"},
                      {"task", "localisation"},
                      {"conditions", {{{"name", "palpate"}, {"mode", "scene"}}}}};
  p["localisation"] = what;
  return p;
}

TEST(LocalisationCases, ANormalCaseIsAcceptedAndScored) {
  test_support::TempDir dir;
  const std::uint64_t seed = normal_hard_seed();
  const auto file = dir.path() / "normal.json";
  write_scene_json(file, generated_case_json(generate_case(seed, CaseDifficulty::hard)));
  const Protocol p = parse_protocol(localisation({{"scene", "normal.json"}}), "p.json", dir.path());
  ASSERT_EQ(p.localisation.cases.size(), 1u);
  EXPECT_TRUE(p.localisation.cases[0].normal());
  EXPECT_EQ(p.localisation.cases[0].name, "case-hard-" + std::to_string(seed));
  // Every mark on a normal case is a false mark; none at all is the right answer.
  EXPECT_EQ(score_localisation({}, {{50, 50}, {80, 60}}, 5).false_marks, 2);
  EXPECT_EQ(score_localisation({}, {}, 5).false_marks, 0);
}

TEST(LocalisationCases, AListOfCasesIsTheItemsOfTheOrder) {
  const std::uint64_t normal = normal_hard_seed();
  const std::filesystem::path scenes = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "scenes";
  const Protocol p = parse_protocol(localisation({{"cases",
                                                   {"phantom_abc_function.json",
                                                    {{"difficulty", "easy"}, {"seed", 7}},
                                                    {{"difficulty", "hard"}, {"seed", normal}}}}}),
                                    "p.json", scenes);
  ASSERT_EQ(p.localisation.cases.size(), 3u);
  EXPECT_TRUE(p.localisation.listed);
  EXPECT_EQ(p.localisation.cases[0].tumors.size(), 3u);
  EXPECT_EQ(p.localisation.cases[1].name, "case-easy-7");
  EXPECT_EQ(p.localisation.cases[1].seed, 7u);
  EXPECT_TRUE(p.localisation.cases[2].normal());
  EXPECT_EQ(order_items(p), 3);
  const SessionPlan plan = make_session_plan(p, 1, 11);
  ASSERT_EQ(plan.trials.size(), 3u);
  std::set<std::string> seen;
  for (const PlannedTrial& t : plan.trials) seen.insert(trial_case(p, t, plan.seed).name);
  EXPECT_EQ(seen.size(), 3u);  // each case once
  // The same case twice in a list is refused.
  EXPECT_THROW(
      parse_protocol(
          localisation({{"cases", {{{"difficulty", "easy"}, {"seed", 7}}, {{"difficulty", "easy"}, {"seed", 7}}}}}),
          "p.json", scenes),
      InputError);
}

TEST(LocalisationCases, GenerateMakesANewCasePerTrialFromTheSessionSeed) {
  nlohmann::json doc = localisation({{"generate", {{"difficulty", "medium"}}}});
  doc["repetitions"] = 6;
  const Protocol p = parse_protocol(doc, "p.json", ".");
  const SessionPlan plan = make_session_plan(p, 1, 42);
  ASSERT_EQ(plan.trials.size(), 6u);
  std::set<std::string> names;
  for (const PlannedTrial& t : plan.trials) {
    const LocalisationCase c = trial_case(p, t, plan.seed);
    EXPECT_EQ(c.difficulty, CaseDifficulty::medium);
    ASSERT_TRUE(c.seed.has_value());
    EXPECT_EQ(*c.seed, generated_case_seed(plan.seed, t.position));
    EXPECT_EQ(c.name, "case-medium-" + std::to_string(*c.seed));
    // The same case again from its stored seed, its truth that of the scene palpated.
    EXPECT_EQ(case_scene(c).tumors.size(), c.tumors.size());
    names.insert(c.name);
  }
  EXPECT_EQ(names.size(), 6u);
  // Another session (seed) gives other cases.
  EXPECT_NE(trial_case(p, plan.trials[0], 43).name, trial_case(p, plan.trials[0], 42).name);
}

TEST(LocalisationCases, ExactlyOneWayOfNamingTheCasesIsRequired) {
  EXPECT_THROW(parse_protocol(localisation({{"tolerance_mm", 5}}), "p.json", "."), InputError);
  EXPECT_THROW(
      parse_protocol(localisation({{"scene", "a.json"}, {"generate", {{"difficulty", "easy"}}}}), "p.json", "."),
      InputError);
  EXPECT_THROW(parse_protocol(localisation({{"generate", {{"difficulty", "tricky"}}}}), "p.json", "."), InputError);
}

}  // namespace
}  // namespace palprig
