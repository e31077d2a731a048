#pragma once
// SimulatedParticipant: a model observer that answers from what the rig actually delivers, so
// whole studies run headless (tests, demos, planning sample sizes).
//
// Discrimination: each finger's felt pressure (mean monitor reading while that finger's
// stimulus was on) is perceived with Gaussian noise (noise_kPa; times sequential_noise_factor
// when the values come one after another and must be held in memory). The observer reports a
// tumor under every finger perceived more than criterion_kPa above the lowest one.
// When the protocol asks for a confidence rating, the observer rates from its decision margin
// (the smallest distance of any finger's perceived excess from the criterion, in units of its
// noise): rating = 1 + floor((Phi(margin) - 0.5) * 2 * levels), at most levels. Deterministic:
// no random number is drawn for it, so sessions without ratings stay bit-identical.
// Response times are log-normal with the mean and sd of paper 002 per mode (4.6 +/- 2.3 s
// three fingers, 8.3 +/- 2.9 s one finger), never before every finger has been felt.
//
// Localisation: the observer rasters the scene with the pen (rows 20 mm apart, a random row
// offset per trial) and watches each finger's pressure above its running minimum. Each bump
// above the detection threshold becomes a candidate at its peak; it is reported with
// probability Phi((peak - threshold) / detection_noise_kPa), marked with Gaussian position
// noise. Small tumors that fall between the fingers' paths are missed, as people miss them.
// When the first pass felt nothing, it palpates again pressing harder (deep_press_force_N) and
// heeding smaller bumps (deep_detection_threshold_kPa), as a clinician does for a deep lesion:
// the tumors of generated medium and hard cases lie too deep to raise 3 kPa under a 2 N press.
// A first pass that felt something ends the trial as before (the phantom's figures unchanged).
#include <cstdint>
#include <deque>
#include <utility>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/observer_skill.hpp"
#include "experiments/participant.hpp"
#include "study/random_source.hpp"
#include "experiments/shifted_input.hpp"
#include "models/finger_layout.hpp"
#include "models/scene.hpp"

namespace palprig {

struct ResponseTimeModel {
  double mean_s = 4.6;
  double sd_s = 2.3;
};

struct SimulatedObserverModel {
  std::uint64_t seed = 1;
  double noise_kPa = 1.7;
  double sequential_noise_factor = 1.3;
  double criterion_kPa = 5.0;
  ResponseTimeModel simultaneous{4.6, 2.3};
  ResponseTimeModel sequential{8.3, 2.9};
  // Localisation.
  double detection_threshold_kPa = 3.0;  // above the plant's hysteresis offset (~2 kPa)
  double detection_noise_kPa = 1.5;
  double mark_noise_mm = 2.0;
  double raster_speed_mm_per_s = 40.0;
  double raster_row_step_mm = 20.0;  // fingers pass 16 mm apart: paths 4 and 16 mm apart
  double press_force_N = 2.0;
  // The second, deeper pass when the first felt nothing (0 N: none).
  double deep_press_force_N = 5.0;
  double deep_detection_threshold_kPa = 1.0;
  ObserverSkill skill;  // a learning pilot trainee (experiments/observer_skill.hpp); default: skilled
};

nlohmann::json to_json(const SimulatedObserverModel& m);

// The simulated observer's rating 1..levels from its decision margin (in noise units, >= 0).
int confidence_from_margin(double margin_in_noise_units, int levels) noexcept;

// "sim:SEED" -> true and the seed; anything else -> false.
bool parse_simulated_participant(const std::string& spec, std::uint64_t& seed);
inline bool is_simulated_participant(const std::string& spec) {
  std::uint64_t seed = 0;
  return parse_simulated_participant(spec, seed);
}

class SimulatedParticipant final : public Participant {
 public:
  // For localisation, `scene` bounds the raster and `layout` places the fingers around the pen.
  SimulatedParticipant(const SimulatedObserverModel& model, const Protocol& protocol, const Scene* scene = nullptr,
                       FingerLayout layout = {});

  bool ready(double) override { return true; }
  void scene_presented(const Scene& scene) override { scene_ = &scene; }
  void trial_started(const PlannedTrial& trial, const Condition& condition, double t_s) override;
  void feel(const FeltSample& sample) override;
  std::optional<Response> answer(double t_s) override;
  InputSource* pen() override { return protocol_.task == TaskKind::localisation ? &pen_ : nullptr; }

 private:
  struct Candidate {
    double x_mm = 0, y_mm = 0, peak_kPa = 0;
  };
  Response discrimination_answer();
  Response localisation_answer();
  void watch_for_bumps(const FeltSample& sample);
  void start_raster(double force_N, double t_s);  // returns through raster_s_
  double raster_s_ = 0;

  SimulatedObserverModel model_;
  const Protocol& protocol_;
  const Scene* scene_;
  FingerLayout layout_;
  RandomSource random_;
  ShiftedInput pen_;

  PresentationMode mode_ = PresentationMode::simultaneous;
  int position_ = 0;  // the trial's position: the learner's case index
  double answer_at_s_ = 0;
  bool answered_ = false;
  std::array<double, kFingerCount> felt_sum_{};
  std::array<int, kFingerCount> felt_count_{};
  std::array<double, kFingerCount> baseline_kPa_{};
  double contact_since_s_ = -1;
  std::vector<Candidate> candidates_;
  bool deep_pass_ = false;                                                  // palpating again, pressing harder
  std::array<std::deque<std::pair<double, double>>, kFingerCount> recent_;  // deep pass: (t, kPa), rising
  double threshold_kPa_ = 0;
};

}  // namespace palprig
