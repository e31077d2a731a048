#pragma once
// The pulse-localisation task (paper 000: find the femoral pulse), protocol "task": "pulse".
// Each trial presents one condition's scene (a function scene with one or more arteries: the
// shipped groin and brachial scenes, or a generated case) under the pen, through the tick's
// pulse stage like every palpation; the participant palpates and marks where the pulse is. The
// mark is scored by its distance to the nearest artery centreline (models/pulse_localisation:
// score_pulse_mark), a hit within the protocol's hit radius. Trial order: every condition
// `repetitions` times, shuffled with the session seed; a resumed session recomputes the same
// order and continues at the first trial not committed.
#include <array>
#include <deque>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/participant.hpp"
#include "experiments/random_source.hpp"
#include "experiments/session_clock.hpp"
#include "experiments/shifted_input.hpp"
#include "experiments/stimulus_output.hpp"
#include "formats/scene_file.hpp"
#include "models/case_generator.hpp"
#include "models/pulse_localisation.hpp"

namespace palprig {

struct PulseCondition {
  std::string name;
  std::filesystem::path scene_file;  // resolved against the protocol's folder
  std::string artery;                // score against this artery; empty: the nearest one
  // "generate": {"difficulty"}: every trial a new generated case (models/case_generator) with a
  // random artery crossing it (generated_pulse_scene), seeded by the session seed and position.
  std::optional<CaseDifficulty> generated;
};

// A generated rehearsal case with one artery crossing the block from its cranial to its caudal
// edge, bending at a random point; deeper and fainter with difficulty (easy 6 mm, medium 10 mm,
// hard 14 mm deep). Same seed, same scene.
SceneFile generated_pulse_scene(std::uint64_t seed, CaseDifficulty difficulty);

struct PulseProtocol {
  std::string source, name, description, bids_task;
  std::vector<PulseCondition> conditions;
  int repetitions = 1;
  double hit_radius_mm = 5.0;
  double max_present_s = 60.0;
  double response_timeout_s = 10.0;
  double inter_trial_s = 2.0;
  nlohmann::json snapshot;
};

bool is_pulse_protocol(const nlohmann::json& document);
// base_dir resolves scene paths; every scene is loaded and must have arteries (InputError).
PulseProtocol parse_pulse_protocol(const nlohmann::json& document, const std::string& source,
                                   const std::filesystem::path& base_dir);
PulseProtocol load_pulse_protocol(const std::filesystem::path& path);

// The order of condition indices for a seed (every condition `repetitions` times, shuffled).
std::vector<int> pulse_trial_order(const PulseProtocol& protocol, std::uint64_t seed);

struct PulseTrialRecord {
  int position = 0;
  std::string condition;
  std::optional<std::uint64_t> scene_seed;  // generated conditions: the case's seed
  bool answered = false;
  double mark_x_mm = 0, mark_y_mm = 0;
  std::string artery;         // the artery scored against
  double distance_mm = 0;     // to its centreline; NaN when not answered
  bool hit = false;
  double onset_s = 0, response_time_s = 0;
};

class PulseParticipant {
 public:
  virtual ~PulseParticipant() = default;
  // Before the first trial and after a pause: true when the participant wants to go on (a
  // person's Ready). The simulated observer is always ready, so its sessions pass no time here.
  virtual bool ready(double /*t_s*/) { return true; }
  // Trial `position` begins on this scene (again from its start after a pause); returns the pen
  // the participant palpates with. An answer belongs to the position it was given for.
  virtual InputSource& trial_started(int position, const PulseCondition& condition, const Scene& scene, double t_s) = 0;
  virtual void feel(const FeltSample& sample) = 0;
  virtual std::optional<Mark> answer(double t_s) = 0;
};

// A trial about to be presented: what a front end needs to show its scene (a generated
// condition's scene is generated_pulse_scene(scene_seed, difficulty)).
struct PulseTrialStart {
  int position = 0;
  int condition = 0;  // index into protocol.conditions
  std::optional<std::uint64_t> scene_seed;
  double onset_s = 0;
};

struct PulseSessionOptions {
  std::uint64_t seed = 1;
  int start_position = 0;
  double period_s = 0.002;  // the pulse is a 72 BPM wave: service the rig often
  const std::atomic<int>* stop = nullptr;  // non-zero: vent and stop (the trial in progress is not kept)
  // true: pause, with the discrimination session's semantics (experiments/session_loop.hpp): vents
  // at once and holds the trial in progress, which is presented again from its start once the
  // pause is lifted and the participant is ready; a pause in the inter-trial interval (the trial
  // is committed) cuts it short. Nothing committed is lost.
  const std::atomic<bool>* pause = nullptr;
  std::function<void(const PulseTrialRecord&)> on_trial;
  std::function<void(const PulseTrialStart&)> on_trial_started;
  // The session waits: `paused` true once a pause is taken (vented, holding); false while it
  // waits for the participant's ready (before the first trial and after a pause).
  std::function<void(int position, bool paused)> on_waiting;
};

struct PulseSessionResult {
  bool completed = false, stopped = false;
  std::string fault;
};

// scenes[i] belongs to protocol.conditions[i].
PulseSessionResult run_pulse_session(const PulseProtocol& protocol, const std::vector<SceneFile>& scenes,
                                     StimulusOutput& output, PulseParticipant& participant, SessionClock& clock,
                                     const PulseSessionOptions& options);

// The simulated participant: sweeps the scene in rows pressing press_force_N and watches each
// finger's pressure for beats: a peak that rises above the lowest pressure of the 0.3 s before
// it AND falls back within the 0.15 s after it (its prominence). A step onto stiffer tissue
// rises but does not fall back, so it is not taken for a pulse. The mark is the finger position
// of the most prominent beat, with Gaussian noise of mark_noise_mm.
struct PulseObserverModel {
  std::uint64_t seed = 1;
  double press_force_N = 2.2;
  double sweep_speed_mm_per_s = 20.0;
  double sweep_row_step_mm = 12.0;
  double mark_noise_mm = 2.0;
};

class SimulatedPulseObserver final : public PulseParticipant {
 public:
  SimulatedPulseObserver(const PulseObserverModel& model, FingerLayout layout) : model_(model), layout_(layout), random_(model.seed) {}
  InputSource& trial_started(int position, const PulseCondition& condition, const Scene& scene, double t_s) override;
  void feel(const FeltSample& sample) override;
  std::optional<Mark> answer(double t_s) override;

 private:
  PulseObserverModel model_;
  FingerLayout layout_;
  RandomSource random_;
  ShiftedInput pen_;
  struct Felt {
    double t_s, kPa, x_mm, y_mm;
  };
  double done_at_s_ = 0;
  std::array<std::deque<Felt>, kFingerCount> history_;
  double best_swing_kPa_ = 0;
  Mark best_{};
};

}  // namespace palprig
