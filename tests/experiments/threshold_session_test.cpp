// Threshold sessions on the simulated rig (every stimulus through tick_direct and the safety
// stage): 20 seeded simulated observers per procedure recover the observer's analytic
// threshold, doubling the noise doubles it; on the real program, SIGKILL mid-session and
// --resume continue the same staircases; the stored trials feed `stats psychometric`.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <cmath>
#include <map>
#include <memory>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/threshold_observer.hpp"
#include "experiments/threshold_session.hpp"
#include "formats/rig_file.hpp"
#include "store/threshold_store.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ChildProcess;
using testing::ScratchDir;

struct SimulatedRig {
  RigConfig rig = load_rig_file(testing::source_dir() / "data" / "rigs" / "simulated.json");
  TickConfig config = make_tick_config(rig, CalibrationModels{});
  std::unique_ptr<RigBackend> backend = make_backend(rig);
  SimulatedRig() { backend->open(); }
};

// The shipped protocol with shorter intervals and pauses (the same procedure, faster to simulate).
ThresholdProtocol quick(const std::string& file) {
  ThresholdProtocol p = load_threshold_protocol(testing::protocols_dir() / file);
  p.timing.interval_s = 0.6;
  p.timing.gap_s = 0.2;
  p.timing.inter_trial_s = 0.1;
  return p;
}

struct ObserverOutcome {
  std::vector<double> mean_estimate;    // per track, over observers
  double mean_trials = 0;               // per track and observer
  double worst_delivery_error_kPa = 0;  // felt increment vs commanded level, mean per observer
};

ObserverOutcome run_observers(const ThresholdProtocol& p, double noise_kPa, int observers) {
  ObserverOutcome out;
  out.mean_estimate.assign(p.tracks.size(), 0.0);
  for (int seed = 1; seed <= observers; ++seed) {
    SimulatedRig rig;
    RigStimulus output(rig.config, *rig.backend);
    ThresholdObserverModel model;
    model.seed = static_cast<std::uint64_t>(seed);
    model.noise_kPa = noise_kPa;
    model.settle_s = 0.3;
    model.response = {0.3, 0.1};
    SimulatedThresholdObserver observer(model);
    std::vector<AdaptiveTrack> tracks;
    for (const auto& spec : p.tracks) tracks.emplace_back(spec);
    SimulatedClock clock;
    ThresholdSessionOptions options;
    options.seed = 1000 + static_cast<std::uint64_t>(seed);
    double delivery_error = 0;
    int trials = 0;
    options.on_trial = [&](const ThresholdTrialRecord& r) {
      const double felt_increment = r.felt_kPa[static_cast<std::size_t>(r.signal_interval)] -
                                    r.felt_kPa[static_cast<std::size_t>(1 - r.signal_interval)];
      delivery_error += felt_increment - r.level_kPa;
      ++trials;
    };
    const auto result = run_threshold_session(p, tracks, output, observer, clock, options);
    EXPECT_TRUE(result.completed) << result.fault;
    out.worst_delivery_error_kPa = std::max(out.worst_delivery_error_kPa, std::abs(delivery_error / trials));
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      EXPECT_TRUE(tracks[t].finished());
      out.mean_estimate[t] += tracks[t].estimate().threshold_kPa / observers;
      out.mean_trials += static_cast<double>(tracks[t].trials()) / observers / static_cast<double>(tracks.size());
    }
  }
  return out;
}

void expect_recovery(const std::string& file, double target_p) {
  const ThresholdProtocol p = quick(file);
  ThresholdObserverModel model;
  model.noise_kPa = 0.8;
  const ObserverOutcome base = run_observers(p, model.noise_kPa, 20);
  // The rig delivered the commanded increments (hysteresis compensation and the safety stage in the path).
  EXPECT_LT(base.worst_delivery_error_kPa, 0.1);
  for (std::size_t t = 0; t < p.tracks.size(); ++t) {
    const double truth = analytic_threshold_kPa(model, p.method, p.tracks[t].fingers, target_p);
    EXPECT_NEAR(base.mean_estimate[t] / truth, 1.0, 0.10)
        << file << " " << p.tracks[t].name << ": " << base.mean_estimate[t] << " kPa vs analytic " << truth;
  }
  const ObserverOutcome doubled = run_observers(p, 2 * model.noise_kPa, 20);
  for (std::size_t t = 0; t < p.tracks.size(); ++t) {
    EXPECT_NEAR(doubled.mean_estimate[t] / base.mean_estimate[t], 2.0, 0.30) << file << " " << p.tracks[t].name;
  }
}

TEST(experiments_threshold_session, staircase_recovers_the_simulated_observers_threshold_on_the_rig) {
  expect_recovery("threshold_1up3down.json", std::pow(0.5, 1.0 / 3.0));  // Levitt 1-up/3-down: 79.4 %
}

TEST(experiments_threshold_session, quest_recovers_the_simulated_observers_threshold_on_the_rig) {
  expect_recovery("threshold_quest.json", 0.82);
}

std::int64_t scalar(SqliteTrialStore& store, const std::string& sql) {
  auto q = store.database().prepare(sql);
  return q.step() ? q.integer(0) : -1;
}

int reported_trials(const std::string& out) {
  int n = 0;
  std::size_t pos = 0;
  while ((pos = out.find("\ntrial ", pos)) != std::string::npos) {
    if (out.find('\n', pos + 1) != std::string::npos) ++n;
    ++pos;
  }
  return n;
}

// Rewrites a schema-3 store as schema 2 wrote it: every threshold row with the JSON state of
// every track after it (replayed here as the old session computed it), user_version 2.
void downgrade_to_schema_2(const std::string& db, const ThresholdProtocol& p) {
  std::vector<ThresholdTrialRecord> rows;
  {
    SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
    for (auto& row : ThresholdStore(store, false).trials()) rows.push_back(row.trial);
  }
  Database raw(db, Database::Mode::read_write_create);
  raw.exec("ALTER TABLE threshold_trials ADD COLUMN state TEXT NOT NULL DEFAULT '[]'");
  std::vector<AdaptiveTrack> tracks;
  for (const auto& spec : p.tracks) tracks.emplace_back(spec);
  replay_tracks(tracks, rows, [&](const ThresholdTrialRecord& r, const std::vector<AdaptiveTrack>& after) {
    auto u = raw.prepare("UPDATE threshold_trials SET state = ?1 WHERE position = ?2");
    u.bind(1, tracks_state(after).dump()).bind(2, r.position);
    u.run();
  });
  raw.exec("PRAGMA user_version = 2");
}

void sigkill_and_resume(bool resume_a_schema_2_store) {
  ScratchDir dir;
  const std::string db = (dir / "threshold.db").string();
  const std::string protocol = (testing::protocols_dir() / "threshold_1up3down.json").string();
  {
    // 20 times real time: about 0.25 s per trial.
    ChildProcess child(
        {"experiment", "run", "--protocol", protocol, "--participant", "sim:3", "--db", db, "--speed", "20"});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
    while (reported_trials(child.out()) < 8 && std::chrono::steady_clock::now() < deadline) child.pump(50);
    ASSERT_GE(reported_trials(child.out()), 8) << "the session did not get going: " << child.out();
    ASSERT_EQ(::kill(child.pid(), SIGKILL), 0);
    EXPECT_EQ(child.wait(), 128 + SIGKILL);
  }
  std::int64_t committed = 0;
  {
    SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
    committed = scalar(store, "SELECT count(*) FROM threshold_trials");
    ASSERT_GE(committed, 8);
    EXPECT_LT(committed, 100) << "the kill came too late to test a resume";
    EXPECT_EQ(scalar(store, "SELECT count(*) FROM sessions WHERE status = 'running'"), 1);
  }
  if (resume_a_schema_2_store) downgrade_to_schema_2(db, load_threshold_protocol(protocol));
  const auto resumed = testing::run_palprig(
      {"experiment", "run", "--protocol", protocol, "--participant", "sim:3", "--db", db, "--resume", "--quiet"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("resumed at trial " + std::to_string(committed + 1)), std::string::npos) << resumed.out;
  EXPECT_NE(resumed.out.find("one-finger: threshold"), std::string::npos) << resumed.out;

  // Replaying every stored answer through fresh tracks reproduces every stored level and state:
  // the resumed part continued the killed staircases (a new staircase would restart at 2 kPa).
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
  EXPECT_EQ(scalar(store, "SELECT count(*) FROM sessions WHERE status = 'completed'"), 1);
  const auto total = scalar(store, "SELECT count(*) FROM threshold_trials");
  EXPECT_EQ(scalar(store, "SELECT max(position) FROM threshold_trials"), total - 1);
  const ThresholdProtocol p = load_threshold_protocol(protocol);
  std::vector<AdaptiveTrack> replay;
  for (const auto& spec : p.tracks) replay.emplace_back(spec);
  auto q = store.database().prepare(
      "SELECT position, track, level_kPa, answered, correct FROM threshold_trials "
      "ORDER BY position");
  int rows = 0;
  while (q.step()) {
    const auto track = static_cast<std::size_t>(q.integer(1));
    ASSERT_LT(track, replay.size());
    EXPECT_DOUBLE_EQ(q.real(2), replay[track].next_level_kPa()) << "position " << q.integer(0);
    if (q.integer(3) != 0) replay[track].record(q.real(2), q.integer(4) != 0);
    ++rows;
  }
  EXPECT_EQ(rows, total);
  for (const auto& t : replay) EXPECT_TRUE(t.finished());
  // Schema 3: no per-row copy of the tracks' state (a row has constant size); a schema-2 store
  // was migrated when the resume opened it, every trial kept (to the current schema, which
  // keeps that: 4 added trials.stimulus_reached_s).
  EXPECT_EQ(store.database().pragma_integer("user_version"), kTrialStoreSchemaVersion);
  EXPECT_GE(kTrialStoreSchemaVersion, 3);
  EXPECT_EQ(scalar(store, "SELECT count(*) FROM pragma_table_info('threshold_trials') WHERE name = 'state'"), 0);

  // The stored trials feed the psychometric fit, one group per track, and the plots.
  const auto fit =
      testing::run_palprig({"stats", "psychometric", db, "--by", "track_name", "--bootstrap", "100", "--json"});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto report = nlohmann::json::parse(fit.out);
  ASSERT_EQ(report["groups"].size(), 2u);
  EXPECT_EQ(report["groups"][0]["guess"].get<double>(), 0.5);
  for (const auto& g : report["groups"]) EXPECT_GT(g["threshold"].get<double>(), 0.0);
  // --plot: PNGs in a build with the chart drawing, a one-line refusal without it.
  const auto plot = testing::run_palprig(
      {"stats", "psychometric", db, "--by", "track_name", "--bootstrap", "50", "--plot", (dir / "plots").string()});
  if (plot.exit_code == 0) {
    EXPECT_GT(std::filesystem::file_size(dir / "plots" / "psychometric_one_finger.png"), 2000u);
    EXPECT_GT(std::filesystem::file_size(dir / "plots" / "psychometric_three_finger.png"), 2000u);
    EXPECT_GT(std::filesystem::file_size(dir / "plots" / "track_session1.png"), 2000u);
  } else {
    EXPECT_EQ(plot.exit_code, 2);
    EXPECT_NE(plot.err.find("chart drawing"), std::string::npos) << plot.err;
  }
}

TEST(experiments_threshold_session, sigkill_and_resume_continue_the_same_staircases) { sigkill_and_resume(false); }

TEST(experiments_threshold_session, a_killed_schema_2_session_is_migrated_and_resumed_with_every_trial) {
  sigkill_and_resume(true);
}

TEST(experiments_threshold_session, protocol_above_the_rigs_p_max_is_refused_before_anything_moves) {
  ScratchDir dir;
  nlohmann::json doc = load_threshold_protocol(testing::protocols_dir() / "threshold_1up3down.json").snapshot;
  doc["threshold"]["reference_kPa"] = 55;  // + 12 kPa > p_max 60 of the simulated rig
  const auto file = dir / "high.json";
  std::ofstream(file) << doc.dump(2);
  const auto r = testing::run_palprig(
      {"experiment", "run", "--protocol", file.string(), "--participant", "sim:1", "--db", (dir / "x.db").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("p_max"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.db"));
}

}  // namespace
}  // namespace palprig

namespace palprig {
namespace {

TEST(experiments_threshold_session, a_person_answers_in_the_terminal_and_q_keeps_the_answers) {
  ScratchDir dir;
  const std::string db = (dir / "person.db").string();
  // Enter starts; "2" and "1" answer two trials (the second and the first interval); q stops.
  const auto r = testing::run_palprig(
      {"experiment", "run", "--protocol", (testing::protocols_dir() / "threshold_1up3down.json").string(),
       "--participant", "P01", "--db", db},
      "\n2\n1\nq\n");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("Which interval was stronger?"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("stopped after 2 trials"), std::string::npos) << r.err;
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
  auto q = store.database().prepare("SELECT response, answered FROM threshold_trials ORDER BY position");
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.integer(0), 1);
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.integer(0), 0);
  EXPECT_FALSE(q.step());
}

}  // namespace
}  // namespace palprig
