#include "experiments/simulated_participant.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace palprig {

namespace {

// Candidates closer than this belong to the same felt bump.
constexpr double kSameBumpMm = 10.0;
// The pressure needs this long after touching down to settle before it sets a baseline.
constexpr double kSettleS = 0.3;
// The deep pass compares each finger's pressure with its lowest of this long before.
constexpr double kDeepWindowS = 0.6;

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

}  // namespace

nlohmann::json to_json(const SimulatedObserverModel& m) {
  nlohmann::json j = {
      {"kind", "model observer"},
      {"seed", m.seed},
      {"noise_kPa", m.noise_kPa},
      {"sequential_noise_factor", m.sequential_noise_factor},
      {"criterion_kPa", m.criterion_kPa},
      {"rt_simultaneous_s", {{"mean", m.simultaneous.mean_s}, {"sd", m.simultaneous.sd_s}}},
      {"rt_sequential_s", {{"mean", m.sequential.mean_s}, {"sd", m.sequential.sd_s}}},
      {"detection_threshold_kPa", m.detection_threshold_kPa},
      {"detection_noise_kPa", m.detection_noise_kPa},
      {"mark_noise_mm", m.mark_noise_mm},
  };
  if (m.skill.learns()) {
    j["learning"] = {{"initial_skill", m.skill.pilot.initial_skill},
                     {"learning_rate_per_case", m.skill.pilot.learning_rate_per_case},
                     {"cases_practised_before", m.skill.cases_practised}};
  }
  return j;
}

int confidence_from_margin(double margin_in_noise_units, int levels) noexcept {
  if (!(margin_in_noise_units > 0)) return 1;
  const double p = normal_cdf(margin_in_noise_units);  // 0.5 .. 1
  const int rating = 1 + static_cast<int>(std::floor((p - 0.5) * 2.0 * levels));
  return std::clamp(rating, 1, levels);
}

bool parse_simulated_participant(const std::string& spec, std::uint64_t& seed) {
  if (spec.rfind("sim:", 0) != 0 || spec.size() == 4) return false;
  const std::string digits = spec.substr(4);
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) || digits.size() > 19) {
    return false;
  }
  seed = std::stoull(digits);
  return true;
}

SimulatedParticipant::SimulatedParticipant(const SimulatedObserverModel& model, const Protocol& protocol,
                                           const Scene* scene, FingerLayout layout)
    : model_(model), protocol_(protocol), scene_(scene), layout_(layout), random_(model.seed) {}

void SimulatedParticipant::trial_started(const PlannedTrial& trial, const Condition& condition, double t_s) {
  mode_ = condition.mode;
  position_ = trial.position;
  answered_ = false;
  felt_sum_.fill(0.0);
  felt_count_.fill(0);
  baseline_kPa_.fill(std::numeric_limits<double>::infinity());
  contact_since_s_ = -1;
  candidates_.clear();

  const Timing& tm = protocol_.timing;
  switch (mode_) {
    case PresentationMode::simultaneous:
      answer_at_s_ = t_s + random_.lognormal_with_mean_sd(model_.simultaneous.mean_s, model_.simultaneous.sd_s);
      break;
    case PresentationMode::sequential: {
      const double all_felt_s = kFingerCount * tm.sequential_step_s + (kFingerCount - 1) * tm.sequential_gap_s;
      const double rt = random_.lognormal_with_mean_sd(model_.sequential.mean_s, model_.sequential.sd_s);
      answer_at_s_ = t_s + std::max(rt, all_felt_s + 0.2);
      break;
    }
    case PresentationMode::scene: {
      deep_pass_ = false;
      threshold_kPa_ = model_.detection_threshold_kPa;
      start_raster(model_.press_force_N, t_s);
      answer_at_s_ = t_s + raster_s_ + random_.lognormal_with_mean_sd(2.0, 1.0);
      break;
    }
  }
}

void SimulatedParticipant::start_raster(double force_N, double t_s) {
  // A fresh raster with a random row offset: which small tumors the fingers pass over varies.
  RasterPlan plan;
  plan.speed_mm_per_s = model_.raster_speed_mm_per_s;
  plan.row_step_mm = model_.raster_row_step_mm;
  plan.force_N = force_N;
  plan.margin_mm = 2.0 + random_.uniform() * model_.raster_row_step_mm;
  auto raster = std::make_unique<RasterInput>(scene_->bounds(), plan);
  raster_s_ = raster->duration_s();
  pen_.restart(std::move(raster), t_s);
  baseline_kPa_.fill(std::numeric_limits<double>::infinity());
  for (auto& w : recent_) w.clear();
  contact_since_s_ = -1;
}

void SimulatedParticipant::feel(const FeltSample& sample) {
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    if (sample.active[f]) {
      felt_sum_[f] += sample.felt_kPa[f];
      ++felt_count_[f];
    }
  }
  if (mode_ == PresentationMode::scene) watch_for_bumps(sample);
}

void SimulatedParticipant::watch_for_bumps(const FeltSample& sample) {
  if (!sample.record || !(sample.record->flags & kInContact) || sample.t_s >= answer_at_s_) {
    contact_since_s_ = -1;
    return;
  }
  if (contact_since_s_ < 0) contact_since_s_ = sample.t_s;
  if (sample.t_s - contact_since_s_ < kSettleS) return;
  const auto fingers = layout_.centres(sample.record->x_mm, sample.record->y_mm);
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    if (deep_pass_) {
      // Against the pressure of the last moments (a monotonic window minimum): the regulator's
      // play holds a steady offset along a row, which a small deep bump must not be lost in.
      auto& w = recent_[f];
      while (!w.empty() && w.back().second >= sample.felt_kPa[f]) w.pop_back();
      w.emplace_back(sample.t_s, sample.felt_kPa[f]);
      while (w.front().first < sample.t_s - kDeepWindowS) w.pop_front();
      baseline_kPa_[f] = w.front().second;
    } else {
      baseline_kPa_[f] = std::min(baseline_kPa_[f], sample.felt_kPa[f]);
    }
    const double excess = sample.felt_kPa[f] - baseline_kPa_[f];
    if (excess < threshold_kPa_) continue;
    auto near = std::find_if(candidates_.begin(), candidates_.end(), [&](const Candidate& c) {
      return std::hypot(c.x_mm - fingers[f].x_mm, c.y_mm - fingers[f].y_mm) < kSameBumpMm;
    });
    if (near == candidates_.end()) {
      candidates_.push_back({fingers[f].x_mm, fingers[f].y_mm, excess});
    } else if (excess > near->peak_kPa) {
      *near = {fingers[f].x_mm, fingers[f].y_mm, excess};
    }
  }
}

std::optional<Response> SimulatedParticipant::answer(double t_s) {
  if (answered_ || t_s < answer_at_s_) return std::nullopt;
  if (mode_ == PresentationMode::scene && candidates_.empty() && !deep_pass_ && model_.deep_press_force_N > 0) {
    // Nothing felt: again, pressing harder, heeding smaller bumps.
    deep_pass_ = true;
    threshold_kPa_ = model_.deep_detection_threshold_kPa;
    start_raster(model_.deep_press_force_N, t_s);
    answer_at_s_ = t_s + raster_s_ + 1.0;
    return std::nullopt;
  }
  answered_ = true;
  return protocol_.task == TaskKind::discrimination ? discrimination_answer() : localisation_answer();
}

Response SimulatedParticipant::discrimination_answer() {
  const double noise =
      model_.noise_kPa * (mode_ == PresentationMode::sequential ? model_.sequential_noise_factor : 1.0);
  std::array<double, kFingerCount> perceived{};
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    const double felt = felt_count_[f] ? felt_sum_[f] / felt_count_[f] : 0.0;
    perceived[f] = felt + noise * random_.normal();
  }
  const double lowest = *std::min_element(perceived.begin(), perceived.end());
  Response r;
  for (std::size_t f = 0; f < kFingerCount; ++f) r.tumor_under[f] = perceived[f] - lowest > model_.criterion_kPa;
  if (protocol_.confidence.asked()) {
    double margin_kPa = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < kFingerCount; ++f) {
      margin_kPa = std::min(margin_kPa, std::abs(perceived[f] - lowest - model_.criterion_kPa));
    }
    // A noiseless observer is sure of every decision not exactly on its criterion.
    const double margin =
        noise > 0 ? margin_kPa / noise : (margin_kPa > 0 ? std::numeric_limits<double>::infinity() : 0.0);
    r.confidence = confidence_from_margin(margin, protocol_.confidence.levels);
  }
  return r;
}

Response SimulatedParticipant::localisation_answer() {
  Response r;
  // A learning trainee reports what it felt with the probability of its skill at this case.
  const double skill = model_.skill.learns() ? model_.skill.at(position_) : 1.0;
  for (const Candidate& c : candidates_) {
    const double p = skill * normal_cdf((c.peak_kPa - threshold_kPa_) / model_.detection_noise_kPa);
    if (random_.uniform() < p) {
      r.marks.push_back(
          {c.x_mm + model_.mark_noise_mm * random_.normal(), c.y_mm + model_.mark_noise_mm * random_.normal()});
    }
  }
  return r;
}

}  // namespace palprig
