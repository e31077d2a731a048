#pragma once
// The simulated participant of the pulse-localisation task (`sim:SEED`).
#include <array>
#include <deque>
#include <optional>

#include "experiments/observer_skill.hpp"
#include "experiments/pulse_session.hpp"
#include "experiments/shifted_input.hpp"
#include "models/finger_layout.hpp"
#include "study/random_source.hpp"

namespace palprig {

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
  ObserverSkill skill;  // a learning pilot trainee (experiments/observer_skill.hpp); default: skilled
};

class SimulatedPulseObserver final : public PulseParticipant {
 public:
  SimulatedPulseObserver(const PulseObserverModel& model, FingerLayout layout)
      : model_(model), layout_(layout), random_(model.seed) {}
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
  int position_ = 0;    // the trial's position: the learner's case index
  SceneBounds bounds_;  // where a learner that missed the pulse marks at random
};

}  // namespace palprig
