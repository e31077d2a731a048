// The pulse-localisation task: protocol validation, the simulated participant finding the
// pulse on the shipped groin and brachial scenes through the rig's pulse stage, the store and
// `stats trials` (hit rate with Wilson intervals, distance median/IQR per condition).
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "experiments/pulse_session.hpp"
#include "experiments/simulated_pulse_observer.hpp"
#include "study/pulse_scene.hpp"
#include "store/sqlite_trial_store.hpp"
#include "core/input_error.hpp"
#include "statistics/statistics_proportion.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

TEST(experiments_pulse_task, shipped_protocol_loads_and_scenes_without_arteries_are_refused) {
  const auto p = load_pulse_protocol(testing::protocols_dir() / "pulse_localisation_000.json");
  ASSERT_EQ(p.conditions.size(), 2u);
  EXPECT_EQ(p.conditions[0].artery, "femoral");
  EXPECT_DOUBLE_EQ(p.hit_radius_mm, 5.0);
  const auto order = pulse_trial_order(p, 42);
  EXPECT_EQ(order.size(), 10u);
  EXPECT_EQ(std::count(order.begin(), order.end(), 0), 5);
  EXPECT_EQ(order, pulse_trial_order(p, 42));

  nlohmann::json doc = p.snapshot;
  doc["conditions"][1]["scene"] = "../scenes/phantom_abc.json";
  try {
    parse_pulse_protocol(doc, "p.json", testing::protocols_dir());
    FAIL() << "a scene without arteries was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("conditions[1].scene"), std::string::npos) << e.what();
  }
  doc = p.snapshot;
  doc["conditions"][0]["artery"] = "radial";
  EXPECT_THROW(parse_pulse_protocol(doc, "p.json", testing::protocols_dir()), InputError);
}

TEST(experiments_pulse_task, simulated_participant_finds_the_pulse_and_stats_trials_reports_it) {
  ScratchDir dir;
  const std::string db = (dir / "pulse.db").string();
  const auto run = testing::run_palprig({"experiment", "run", "--protocol",
                                         (testing::protocols_dir() / "pulse_localisation_000.json").string(),
                                         "--participant", "sim:1", "--db", db, "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto stats = testing::run_palprig({"stats", "trials", db, "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  const auto j = nlohmann::json::parse(stats.out);
  ASSERT_EQ(j["conditions"].size(), 2u);
  int hits = 0, trials = 0;
  for (const auto& c : j["conditions"]) {
    trials += c["trials"].get<int>();
    hits += c["hits"].get<int>();
    // Marks land near the artery: a mark placed at random over the 160 x 120 mm pad would have
    // a median distance of tens of millimetres.
    EXPECT_LT(c["distance_median_mm"].get<double>(), 6.0) << c.dump();
    const auto w = stats::wilson_interval(c["hits"].get<int>(), c["trials"].get<int>(), 0.95);
    EXPECT_DOUBLE_EQ(c["hit_rate_low"].get<double>(), w.lower);
    EXPECT_DOUBLE_EQ(c["hit_rate_high"].get<double>(), w.upper);
    EXPECT_LE(c["distance_q1_mm"].get<double>(), c["distance_median_mm"].get<double>());
  }
  EXPECT_EQ(trials, 10);
  EXPECT_GE(hits, 5);

  // A person cannot run it from the terminal (no pen input there): refused before anything moves.
  const auto person = testing::run_palprig({"experiment", "run", "--protocol",
                                            (testing::protocols_dir() / "pulse_localisation_000.json").string(),
                                            "--participant", "P01", "--db", (dir / "p.db").string()});
  EXPECT_EQ(person.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "p.db"));
}

}  // namespace
}  // namespace palprig

namespace palprig {
namespace {

TEST(experiments_pulse_task, generated_cases_carry_an_artery_and_the_participant_finds_it) {
  // Same seed, same case; different seeds, different courses.
  const SceneFile a = generated_pulse_scene(11, CaseDifficulty::medium);
  const SceneFile b = generated_pulse_scene(11, CaseDifficulty::medium);
  const SceneFile c = generated_pulse_scene(12, CaseDifficulty::medium);
  ASSERT_NE(a.scene->pulse(), nullptr);
  ASSERT_EQ(a.scene->pulse()->size(), 1u);
  const auto& pa = a.scene->pulse()->artery(0).spec().path;
  EXPECT_DOUBLE_EQ(pa[1].x_mm, b.scene->pulse()->artery(0).spec().path[1].x_mm);
  EXPECT_NE(pa[1].x_mm, c.scene->pulse()->artery(0).spec().path[1].x_mm);
  EXPECT_DOUBLE_EQ(a.scene->pulse()->artery(0).spec().depth_mm, 10.0);

  ScratchDir dir;
  const std::string db = (dir / "gen.db").string();
  const auto run = testing::run_palprig({"experiment", "run", "--protocol",
                                         (testing::protocols_dir() / "pulse_generated.json").string(), "--participant",
                                         "sim:2", "--db", db, "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto stats = testing::run_palprig({"stats", "trials", db, "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  const auto j = nlohmann::json::parse(stats.out);
  ASSERT_EQ(j["conditions"].size(), 2u);
  for (const auto& cond : j["conditions"]) {
    EXPECT_EQ(cond["trials"].get<int>(), 4);
    EXPECT_LT(cond["distance_median_mm"].get<double>(), 8.0) << cond.dump();
  }
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
  auto q = store.database().prepare("SELECT count(DISTINCT scene_seed) FROM pulse_trials WHERE scene_seed IS NOT NULL");
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.integer(0), 8) << "every trial a new case, its seed stored";
}

}  // namespace
}  // namespace palprig
