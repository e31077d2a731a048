// Protocol files: the shipped paper 002 protocols load and mean what the paper says; bad files
// are refused with the field and the reason, before any stimulus.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "study/protocol.hpp"
#include "core/input_error.hpp"

namespace palprig {
namespace {

const std::filesystem::path kProtocols = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "protocols";

nlohmann::json minimal_protocol() {
  return nlohmann::json::parse(R"({
    "version": 1, "name": "mini", "task": "discrimination",
    "levels_kPa": [0, 30],
    "combinations": {"how_chosen": "test", "list_kPa": [[0, 0, 0], [30, 0, 0], [0, 30, 30]]},
    "conditions": [{"name": "a", "mode": "simultaneous"}, {"name": "b", "mode": "sequential"}]
  })");
}

// The field path an InputError names, or "" when parsing succeeds.
std::string protocol_refusal(const nlohmann::json& doc) {
  try {
    parse_protocol(doc, "test.json", ".");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "test.json");
    return e.where();
  }
  return "";
}

TEST(experiments_protocol, paper_002_discrimination_set) {
  const Protocol p = load_protocol(kProtocols / "discrimination_002.json");
  EXPECT_EQ(p.task, TaskKind::discrimination);
  EXPECT_EQ(p.levels_kPa, (std::vector<double>{0, 10, 30}));
  ASSERT_EQ(p.combinations.size(), 14u);
  EXPECT_FALSE(p.combinations_how_chosen.empty());
  int absent = 0, one = 0, two = 0;
  std::set<std::string> labels;
  for (const auto& c : p.combinations) {
    labels.insert(c.label);
    const int n = c.tumor[0] + c.tumor[1] + c.tumor[2];
    (n == 0 ? absent : n == 1 ? one : two)++;
    // The rule itself: tumor fingers are exactly those above the lowest pressure.
    const double lo = std::min({c.pressure_kPa[0], c.pressure_kPa[1], c.pressure_kPa[2]});
    for (int f = 0; f < 3; ++f) EXPECT_EQ(c.tumor[f], c.pressure_kPa[f] > lo) << c.label;
    if (n == 2) {
      EXPECT_TRUE(c.tumor[1]) << "two-finger tumors are adjacent (middle finger included): " << c.label;
    }
  }
  EXPECT_EQ(labels.size(), 14u);
  EXPECT_EQ(absent, 3);
  EXPECT_EQ(one, 9);
  EXPECT_EQ(two, 2);
  // 3 values x 14 trials per participant and mode, as in the paper's 3 x 14 x 12 = 504.
  EXPECT_EQ(3 * p.combinations.size() * 12, 504u);
  ASSERT_EQ(p.conditions.size(), 2u);
  EXPECT_EQ(p.conditions[0].mode, PresentationMode::simultaneous);
  EXPECT_EQ(p.conditions[1].mode, PresentationMode::sequential);
  EXPECT_EQ(p.counterbalancing, Counterbalancing::alternate);
}

TEST(experiments_protocol, paper_002_localisation_has_tumors_a_b_c) {
  const Protocol p = load_protocol(kProtocols / "localisation_002.json");
  EXPECT_EQ(p.task, TaskKind::localisation);
  ASSERT_EQ(p.localisation.cases.size(), 1u);
  ASSERT_EQ(p.localisation.cases[0].tumors.size(), 3u);
  EXPECT_EQ(p.localisation.cases[0].tumors[0].name, "A");
  EXPECT_EQ(p.localisation.cases[0].tumors[2].name, "C");
  EXPECT_EQ(p.conditions[0].mode, PresentationMode::scene);
}

TEST(experiments_protocol, tumor_rule_classifies_and_refuses) {
  const std::vector<std::pair<int, int>> adjacent = {{0, 1}, {1, 2}};
  FingerFlags tumor{};
  std::string why;
  EXPECT_TRUE(classify_by_tumor_rule({10, 10, 10}, adjacent, tumor, why));
  EXPECT_EQ(tumor, (FingerFlags{false, false, false}));
  EXPECT_TRUE(classify_by_tumor_rule({10, 30, 10}, adjacent, tumor, why));
  EXPECT_EQ(tumor, (FingerFlags{false, true, false}));
  EXPECT_TRUE(classify_by_tumor_rule({30, 30, 0}, adjacent, tumor, why));
  EXPECT_EQ(tumor, (FingerFlags{true, true, false}));
  EXPECT_FALSE(classify_by_tumor_rule({0, 10, 30}, adjacent, tumor, why));
  EXPECT_NE(why.find("three different"), std::string::npos);
  EXPECT_FALSE(classify_by_tumor_rule({30, 0, 30}, adjacent, tumor, why));
  EXPECT_NE(why.find("not adjacent"), std::string::npos);
}

TEST(experiments_protocol, minimal_file_gets_defaults) {
  const Protocol p = parse_protocol(minimal_protocol(), "test.json", ".");
  EXPECT_EQ(p.repetitions, 1);
  EXPECT_EQ(p.bids_task, "mini");
  EXPECT_EQ(p.randomisation.scheme, RandomScheme::full);
  EXPECT_EQ(p.adjacent_fingers.size(), 2u);
}

TEST(experiments_protocol, refuses_bad_files_naming_the_field) {
  auto doc = minimal_protocol();
  doc["levels_kpa"] = {0, 30};  // typo of a real field
  EXPECT_EQ(protocol_refusal(doc), "levels_kpa");

  doc = minimal_protocol();
  doc["levels_kPa"] = nlohmann::json::array();
  doc["combinations"]["list_kPa"] = {{0, 0, 0}};
  EXPECT_EQ(protocol_refusal(doc), "levels_kPa");

  doc = minimal_protocol();
  doc["combinations"]["list_kPa"][1] = {30, 10, 0};
  EXPECT_EQ(protocol_refusal(doc), "combinations.list_kPa[1][1]");  // 10 is not a level

  doc = minimal_protocol();
  doc["levels_kPa"] = {0, 10, 30};
  doc["combinations"]["list_kPa"][1] = {30, 10, 0};
  EXPECT_EQ(protocol_refusal(doc), "combinations.list_kPa[1]");  // three different pressures

  doc = minimal_protocol();
  doc["combinations"]["list_kPa"][2] = {30, 0, 30};
  EXPECT_EQ(protocol_refusal(doc), "combinations.list_kPa[2]");  // fingers 1 and 3 are not adjacent

  doc = minimal_protocol();
  doc["combinations"]["list_kPa"][2] = {30, 0, 0};
  EXPECT_EQ(protocol_refusal(doc), "combinations.list_kPa[2]");  // duplicate

  doc = minimal_protocol();
  doc["version"] = 2;
  EXPECT_EQ(protocol_refusal(doc), "version");

  doc = minimal_protocol();
  doc["conditions"][1]["mode"] = "scene";
  EXPECT_EQ(protocol_refusal(doc), "conditions[1].mode");

  doc = minimal_protocol();
  doc["conditions"] = nlohmann::json::array();
  EXPECT_EQ(protocol_refusal(doc), "conditions");

  doc = minimal_protocol();
  doc["timing"] = {{"inter_trial_s", -1}};
  EXPECT_EQ(protocol_refusal(doc), "timing.inter_trial_s");

  doc = minimal_protocol();
  doc["repetitions"] = 2;
  doc["blocks_per_condition"] = 4;  // 6 trials per condition do not split into 4 blocks
  EXPECT_EQ(protocol_refusal(doc), "blocks_per_condition");
}

TEST(experiments_protocol, refuses_impossible_ordering_constraints) {
  auto doc = minimal_protocol();
  doc["repetitions"] = 4;
  doc["randomisation"] = {{"scheme", "full"}, {"min_distance", 3}};
  EXPECT_EQ(protocol_refusal(doc), "");      // 3 kinds x 4: a b c a b c ... works
  doc["randomisation"]["min_distance"] = 4;  // needs (4 - 1) * 4 + 3 = 15 > 12 positions
  EXPECT_EQ(protocol_refusal(doc), "randomisation");

  doc = minimal_protocol();
  doc["repetitions"] = 2;
  doc["randomisation"] = {{"scheme", "blocked"}, {"min_distance", 4}};  // blocked runs of 3 kinds
  EXPECT_EQ(protocol_refusal(doc), "randomisation.min_distance");

  doc = minimal_protocol();
  doc["combinations"]["list_kPa"] = {{0, 0, 0}};
  doc["repetitions"] = 3;
  doc["randomisation"] = {{"scheme", "full"}, {"max_repeats_in_a_row", 2}};  // one kind, 3 in a row
  EXPECT_EQ(protocol_refusal(doc), "randomisation");

  doc = minimal_protocol();
  doc["repetitions"] = 2;
  doc["combinations"]["list_kPa"] = {{0, 0, 0}};
  doc["randomisation"] = {{"scheme", "fixed"}, {"max_repeats_in_a_row", 1}};
  EXPECT_EQ(protocol_refusal(doc), "randomisation");
}

}  // namespace
}  // namespace palprig
