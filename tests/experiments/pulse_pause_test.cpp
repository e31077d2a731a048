// Pause and Ready in a pulse-localisation session: run_pulse_session on a real
// RigStimulus over the simulated rig's backend, on a scripted simulated clock that asks for the
// pause and lifts it at given times. A pause vents at once (the regulators' monitors fall to 0),
// holds the trial in progress and presents it again from its start once the participant is
// ready again; nothing committed is lost.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "experiments/pulse_session.hpp"
#include "experiments/rig_stimulus.hpp"
#include "formats/rig_file.hpp"
#include "tests/support/support.hpp"

namespace palprig {
namespace {

// Simulated time; the pause flag goes up at pause_on_s and down at pause_off_s.
class ScriptedPauseClock final : public SessionClock {
 public:
  ScriptedPauseClock(RunControl& pause, double on_s, double off_s) : pause_(pause), on_s_(on_s), off_s_(off_s) {}
  double now_s() override { return t_s_; }
  void wait_until(double t_s) override {
    if (t_s > t_s_) t_s_ = t_s;
    pause_.set_paused(t_s_ >= on_s_ && t_s_ < off_s_);
  }

 private:
  RunControl& pause_;
  double t_s_ = 0, on_s_, off_s_;
};

// Presses 2.5 N at one point over the femoral artery; ready from ready_from_s on; marks that
// point 3 s into each presentation.
class PressingParticipant final : public PulseParticipant {
 public:
  struct Pen final : InputSource {
    double x_mm = 0, y_mm = 0;
    TouchSample latest(double t_s) noexcept override { return {t_s, x_mm, y_mm, 2.5, true}; }
    double duration_s() const noexcept override { return 0; }
    std::string describe() const override { return "fixed press"; }
  };
  PressingParticipant(double x_mm, double y_mm) { pen_.x_mm = x_mm, pen_.y_mm = y_mm; }

  bool ready(double t_s) override {
    ++ready_asked;
    return t_s >= ready_from_s;
  }
  InputSource& trial_started(int position, const PulseCondition&, const Scene&, double t_s) override {
    started.push_back(position);
    onset_s_ = t_s;
    return pen_;
  }
  void feel(const FeltSample&) override {}
  std::optional<Mark> answer(double t_s) override {
    if (t_s - onset_s_ < 3.0) return std::nullopt;
    return Mark{pen_.x_mm, pen_.y_mm};
  }

  double ready_from_s = 0;
  int ready_asked = 0;
  std::vector<int> started;

 private:
  Pen pen_;
  double onset_s_ = 0;
};

// The rig stimulus, with every serviced monitor reading kept with its time.
class WatchedOutput final : public StimulusOutput {
 public:
  explicit WatchedOutput(StimulusOutput& inner) : inner_(inner) {}
  void hold(const ChannelPressures& p, double t_s) override { inner_.hold(p, t_s); }
  void palpate(const Scene& scene, InputSource& pen, double t_s) override { inner_.palpate(scene, pen, t_s); }
  void vent(double t_s) override { inner_.vent(t_s); }
  ChannelPressures service(double t_s) override {
    const ChannelPressures felt = inner_.service(t_s);
    readings.push_back({t_s, felt});
    return felt;
  }
  std::string describe() const override { return inner_.describe(); }
  const TelemetryRecord* last_record() const noexcept override { return inner_.last_record(); }

  struct Reading {
    double t_s;
    ChannelPressures kPa;
  };
  std::vector<Reading> readings;

 private:
  StimulusOutput& inner_;
};

double highest_kPa(const std::vector<WatchedOutput::Reading>& readings, double from_s, double to_s) {
  double most = 0;
  for (const auto& r : readings)
    if (r.t_s >= from_s && r.t_s < to_s)
      for (double p : r.kPa) most = std::max(most, p);
  return most;
}

PulseProtocol groin_only() {
  auto p = load_pulse_protocol(testing::protocols_dir() / "pulse_localisation_000.json");
  nlohmann::json doc = p.snapshot;
  doc["conditions"] = nlohmann::json::array({doc["conditions"][0]});  // the groin, femoral artery
  doc["repetitions"] = 2;
  doc["pulse"]["inter_trial_s"] = 0.5;
  return parse_pulse_protocol(doc, "groin.json", testing::protocols_dir());
}

TEST(experiments_pulse_pause, pause_vents_holds_and_presents_the_same_trial_again_after_the_ready) {
  const PulseProtocol protocol = groin_only();
  std::vector<SceneFile> scenes;
  for (const auto& c : protocol.conditions) scenes.push_back(load_scene_file(c.scene_file));
  const RigConfig rig = default_rig();
  auto backend = make_backend(rig);
  backend->open();
  RigStimulus rig_output(make_tick_config(rig, CalibrationModels{}), *backend);
  WatchedOutput output(rig_output);

  RunControl pause;
  ScriptedPauseClock clock(pause, 1.5, 3.0);    // paused 1.5 s into trial 1, lifted at 3 s
  PressingParticipant participant(80.5, 45.0);  // on the femoral artery's course (x 79..82 mm)
  std::vector<PulseTrialRecord> committed;
  std::vector<std::pair<int, bool>> waits;
  PulseSessionOptions options;
  options.seed = 7;
  options.control = &pause;
  options.on_trial = [&](const PulseTrialRecord& r) { committed.push_back(r); };
  options.on_waiting = [&](int position, bool paused) {
    waits.emplace_back(position, paused);
    if (paused) participant.ready_from_s = 3.5;  // after the pause the participant takes half a second
  };
  const PulseSessionResult result = run_pulse_session(protocol, scenes, output, participant, clock, options);
  backend->vent();
  backend->close();
  ASSERT_TRUE(result.completed) << result.fault;

  // Pressing over the artery before the pause: the fingers feel pressure (about 12 kPa).
  EXPECT_GT(highest_kPa(output.readings, 1.0, 1.5), 5.0);
  // The pause vents at once: within 0.3 s every regulator reads 0 but for the simulated
  // monitors' noise (peaks of 0.35 kPa seen), and stays there until the trial starts again.
  EXPECT_LT(highest_kPa(output.readings, 1.8, 3.5), 0.5);
  // The held trial is presented again from its start, after the Ready (3.5 s), then trial 2.
  EXPECT_EQ(participant.started, (std::vector<int>{0, 0, 1}));
  ASSERT_EQ(waits.size(), 2u);
  EXPECT_EQ(waits[0], std::make_pair(0, true));   // holding, vented
  EXPECT_EQ(waits[1], std::make_pair(0, false));  // waiting for the participant's Ready
  ASSERT_EQ(committed.size(), 2u);                // each trial committed once
  EXPECT_EQ(committed[0].position, 0);
  EXPECT_EQ(committed[1].position, 1);
  EXPECT_GE(committed[0].onset_s, 3.5);
  EXPECT_NEAR(committed[0].response_time_s, 3.0, 0.01);
  EXPECT_TRUE(committed[0].answered);
  EXPECT_LT(committed[0].distance_mm, protocol.hit_radius_mm);
}

TEST(experiments_pulse_pause, stop_while_paused_keeps_what_was_committed) {
  const PulseProtocol protocol = groin_only();
  std::vector<SceneFile> scenes;
  for (const auto& c : protocol.conditions) scenes.push_back(load_scene_file(c.scene_file));
  const RigConfig rig = default_rig();
  auto backend = make_backend(rig);
  backend->open();
  RigStimulus output(make_tick_config(rig, CalibrationModels{}), *backend);
  RunControl control;
  ScriptedPauseClock clock(control, 5.0, 1e9);  // paused in trial 2 (trial 1 ends at 3 s + 0.5 s gap), never lifted
  PressingParticipant participant(80.5, 45.0);
  std::vector<PulseTrialRecord> committed;
  PulseSessionOptions options;
  options.control = &control;
  options.on_trial = [&](const PulseTrialRecord& r) { committed.push_back(r); };
  options.on_waiting = [&](int, bool paused) {
    if (paused) control.request_stop();  // the experimenter aborts while paused
  };
  const PulseSessionResult result = run_pulse_session(protocol, scenes, output, participant, clock, options);
  backend->vent();
  backend->close();
  EXPECT_TRUE(result.stopped);
  ASSERT_EQ(committed.size(), 1u);
  EXPECT_EQ(committed[0].position, 0);
  EXPECT_EQ(participant.started, (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace palprig
