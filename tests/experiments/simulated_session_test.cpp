// Whole sessions in process: the runner drives the simulated rig through the controller's tick,
// the model observer answers from what the actuators deliver, the store keeps every trial.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/session_loop.hpp"
#include "sessions/session_setup.hpp"
#include "experiments/simulated_participant.hpp"
#include "experiments/trial_cases.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_summary.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

using testing::ScratchDir;

struct SimulatedRigSetup {
  RigConfig rig = load_rig_file(testing::source_dir() / "data" / "rigs" / "simulated.json");
  TickConfig config = make_tick_config(rig, CalibrationModels{});
  std::unique_ptr<RigBackend> backend = make_backend(rig);
  SimulatedRigSetup() { backend->open(); }
};

TEST(experiments_simulated_session, discrimination_on_the_simulated_rig) {
  ScratchDir dir;
  const Protocol p = load_protocol(testing::protocols_dir() / "discrimination_002.json");
  SqliteTrialStore store(dir / "s.db", TrialStore::Access::read_write);
  SessionRequest request;
  request.participant_code = "sim:11";
  request.simulated = true;
  const OpenedSession session = open_session(store, p, request);

  SimulatedRigSetup rig;
  RigStimulus output(rig.config, *rig.backend);
  SimulatedObserverModel model;
  model.seed = 11;
  SimulatedParticipant participant(model, p);
  std::vector<TrialRecord> seen;
  SessionRecorder recorder(store, session.session_id, {}, [&](const TrialRecord& t) { seen.push_back(t); });
  TrialRunner runner(p, session.plan, 0, output, recorder);
  SimulatedClock clock;
  SessionLoopOptions options;
  options.output = &output;
  const SessionLoopResult result = run_session_loop(runner, participant, clock, options);
  ASSERT_TRUE(result.completed) << result.fault;
  ASSERT_EQ(seen.size(), session.plan.trials.size());
  EXPECT_EQ(recorder.committed(), static_cast<int>(seen.size()));

  // The actuators delivered the commanded levels (within the plant's hysteresis and lag).
  for (const TrialRecord& t : seen) {
    if (t.mode != PresentationMode::simultaneous) continue;
    for (std::size_t f = 0; f < kFingerCount; ++f)
      EXPECT_NEAR(t.felt_kPa[f], t.stimulus_kPa[f], 3.0) << t.combination_label;
  }
  // Response times follow the mode: sequential needs every finger felt first.
  const Timing& tm = p.timing;
  const double sequence_s = 3 * tm.sequential_step_s + 2 * tm.sequential_gap_s;
  for (const TrialRecord& t : seen) {
    ASSERT_TRUE(t.answered);
    if (t.mode == PresentationMode::sequential) {
      EXPECT_GE(t.response_time_s, sequence_s);
    }
  }
  // A good observer: most finger values right.
  SummaryOptions options_all;
  const TrialSummary s = summarise_trials(store, options_all);
  ASSERT_EQ(s.rows.size(), 1u);
  EXPECT_GT(s.rows[0].measures.acc.value, 0.8);
}

TEST(experiments_simulated_session, observer_without_noise_is_perfect_and_noise_hurts) {
  const Protocol p = load_protocol(testing::protocols_dir() / "discrimination_002.json");
  auto accuracy = [&](double noise_kPa) {
    SimulatedRigSetup rig;
    RigStimulus output(rig.config, *rig.backend);
    SimulatedObserverModel model;
    model.seed = 3;
    model.noise_kPa = noise_kPa;
    SimulatedParticipant participant(model, p);
    const SessionPlan plan = make_session_plan(p, 1, 3);
    class Tally final : public RunnerListener {
     public:
      void on_trial_completed(const TrialRecord& t) override {
        for (Outcome o : t.finger_outcomes) counts.add(o);
      }
      ConfusionCounts counts;
    } tally;
    TrialRunner runner(p, plan, 0, output, tally);
    SimulatedClock clock;
    SessionLoopOptions options;
    EXPECT_TRUE(run_session_loop(runner, participant, clock, options).completed);
    return static_cast<double>(tally.counts.tp + tally.counts.tn) / static_cast<double>(tally.counts.total());
  };
  EXPECT_DOUBLE_EQ(accuracy(0.0), 1.0);
  EXPECT_LT(accuracy(6.0), 0.9);
}

TEST(experiments_simulated_session, localisation_sweeps_the_scene_and_marks_tumors) {
  const Protocol p = load_protocol(testing::protocols_dir() / "localisation_002.json");
  SimulatedRigSetup rig;
  RigStimulus output(rig.config, *rig.backend);
  SimulatedObserverModel model;
  model.seed = 2;
  model.raster_row_step_mm = 6.0;  // a thorough raster finds every tumor
  SimulatedParticipant participant(model, p, nullptr, rig.config.layout);
  const SessionPlan plan = make_session_plan(p, 1, 2);
  TrialCases cases(p, plan.seed);
  class Keep final : public RunnerListener {
   public:
    void on_trial_completed(const TrialRecord& t) override { trials.push_back(t); }
    std::vector<TrialRecord> trials;
  } keep;
  TrialRunner runner(p, plan, 0, output, keep, &cases, participant.pen());
  SimulatedClock clock;
  SessionLoopOptions options;
  options.output = &output;
  ASSERT_TRUE(run_session_loop(runner, participant, clock, options).completed);
  ASSERT_EQ(keep.trials.size(), 1u);
  const TrialRecord& t = keep.trials[0];
  ASSERT_TRUE(t.answered);
  for (const TumorScore& s : t.localisation.tumors) EXPECT_TRUE(s.hit) << s.tumor;
  EXPECT_LE(t.localisation.false_marks, 1);
}

TEST(experiments_simulated_session, rig_faults_stop_the_session_vented) {
  const Protocol p = load_protocol(testing::protocols_dir() / "discrimination_002.json");
  SimulatedRigSetup rig;
  TickConfig config = rig.config;
  RigStimulus output(config, *rig.backend);
  // A stimulus the safety stage cannot pass: NaN latches a fault and vents.
  EXPECT_THROW(output.hold({std::nan(""), 0, 0}, 0.0), RigFault);
  EXPECT_THROW(output.service(0.1), RigFault) << "the fault stays latched";
}

}  // namespace
}  // namespace palprig
