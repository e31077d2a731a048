// Curriculum files (study/curriculum.hpp): the shipped example loads and means what it says;
// a bad file is refused with one line naming the file, the field and what was expected.
#include "study/curriculum.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/input_error.hpp"

namespace palprig {
namespace {

const std::filesystem::path kCurricula = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "curricula";

nlohmann::json minimal_curriculum() {
  return nlohmann::json::parse(R"({
    "version": 1, "kind": "curriculum", "name": "mini",
    "levels": [{"name": "easy", "cases": {"generate": "easy"}, "benchmark": {"found_min": 0.9}}]
  })");
}

// "file: field: expected" of the refusal, or "accepted".
std::string curriculum_refusal(const nlohmann::json& doc) {
  try {
    parse_curriculum(doc, "course.json", kCurricula);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "course.json");
    return e.where() + ": " + e.expected();
  }
  return "accepted";
}

TEST(Curriculum, ShippedExampleLoadsEveryKindOfLevel) {
  const Curriculum c = load_curriculum(kCurricula / "palpation_basics.json");
  EXPECT_EQ(c.name, "palpation-basics");
  ASSERT_EQ(c.levels.size(), 5u);
  EXPECT_EQ(c.levels[0].cases, LevelCases::generated_tumors);
  EXPECT_EQ(c.levels[0].difficulty, CaseDifficulty::easy);
  EXPECT_EQ(c.levels[0].cases_per_session, 4);
  EXPECT_EQ(c.levels[0].benchmark.found_min, 0.85);
  EXPECT_EQ(c.levels[0].benchmark.consecutive_sessions, 2);
  EXPECT_EQ(c.levels[2].cases, LevelCases::scene_set);
  ASSERT_EQ(c.levels[2].scenes.size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(c.levels[2].scenes[0]));
  EXPECT_EQ(c.levels[2].benchmark.consecutive_sessions, 3);
  EXPECT_EQ(c.levels[3].benchmark.normal_called_min, 0.5);
  EXPECT_EQ(c.levels[3].feedback, Feedback::practice);
  EXPECT_EQ(c.levels[4].cases, LevelCases::generated_pulse);
  EXPECT_DOUBLE_EQ(c.cusum.unacceptable_failure_rate, 0.3);
  EXPECT_EQ(c.cusum.horizon_cases, 60);
  EXPECT_DOUBLE_EQ(c.pilot.learning_rate_per_case, 0.08);
  EXPECT_EQ(level_index(c, "phantom"), 2);
}

TEST(Curriculum, MinimalFileTakesTheDefaults) {
  const Curriculum c = parse_curriculum(minimal_curriculum(), "course.json", kCurricula);
  EXPECT_EQ(c.levels[0].cases_per_session, 4);
  EXPECT_EQ(c.levels[0].feedback, Feedback::all);
  EXPECT_DOUBLE_EQ(c.tolerance_mm, 5.0);
  EXPECT_DOUBLE_EQ(c.pilot.initial_skill, 0.3);
}

TEST(Curriculum, BadFilesAreRefusedNamingTheField) {
  auto doc = minimal_curriculum();
  doc["version"] = 2;
  EXPECT_NE(curriculum_refusal(doc).find("version"), std::string::npos);

  doc = minimal_curriculum();
  doc["levels"] = nlohmann::json::array();
  EXPECT_EQ(curriculum_refusal(doc), "levels: at least one level");

  doc = minimal_curriculum();
  doc["levels"][0]["cases"] = {{"generate", "tricky"}};
  EXPECT_NE(curriculum_refusal(doc).find("levels[0].cases.generate"), std::string::npos);

  doc = minimal_curriculum();
  doc["levels"][0]["cases"] = {{"generate", "easy"}, {"pulse", "easy"}};
  EXPECT_NE(curriculum_refusal(doc).find("exactly one of"), std::string::npos);

  doc = minimal_curriculum();
  doc["levels"][0]["cases"] = {{"scenes", {"no_such_scene.json"}}};
  EXPECT_NE(curriculum_refusal(doc).find("no_such_scene.json"), std::string::npos);

  doc = minimal_curriculum();
  doc["levels"][0]["benchmark"] = {{"found_min", 1.5}};
  EXPECT_NE(curriculum_refusal(doc).find("levels[0].benchmark.found_min"), std::string::npos);

  doc = minimal_curriculum();
  doc["levels"][0]["benchmark"] = {{"consecutive_sessions", 2}};
  EXPECT_NE(curriculum_refusal(doc).find("at least one measure"), std::string::npos);

  doc = minimal_curriculum();
  doc["levels"].push_back(doc["levels"][0]);
  EXPECT_NE(curriculum_refusal(doc).find("levels[1].name"), std::string::npos);

  doc = minimal_curriculum();
  doc["cusum"] = {{"acceptable_failure_rate", 0.3}, {"unacceptable_failure_rate", 0.2}};
  EXPECT_NE(curriculum_refusal(doc).find("cusum.unacceptable_failure_rate"), std::string::npos);

  doc = minimal_curriculum();
  doc["levels"][0]["cases_per_sesion"] = 3;  // a typo is refused, not ignored
  EXPECT_NE(curriculum_refusal(doc).find("cases_per_sesion"), std::string::npos);

  doc = minimal_curriculum();
  doc["kind"] = "scene";
  EXPECT_NE(curriculum_refusal(doc).find("kind"), std::string::npos);
}

TEST(Curriculum, UnknownLevelNameIsRefusedListingTheLevels) {
  const Curriculum c = load_curriculum(kCurricula / "palpation_basics.json");
  try {
    level_index(c, "expert");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'easy tumors'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace palprig
