#include "experiments/simulated_pulse_observer.hpp"

#include <algorithm>
#include <memory>

namespace palprig {

InputSource& SimulatedPulseObserver::trial_started(int position, const PulseCondition&, const Scene& scene,
                                                   double t_s) {
  position_ = position;
  bounds_ = scene.bounds();
  // A pen raster (the model's sweep_* fields keep their stored names).
  RasterPlan plan;
  plan.speed_mm_per_s = model_.sweep_speed_mm_per_s;
  plan.row_step_mm = model_.sweep_row_step_mm;
  plan.force_N = model_.press_force_N;
  plan.margin_mm = 2.0 + random_.uniform() * model_.sweep_row_step_mm;
  auto raster = std::make_unique<RasterInput>(scene.bounds(), plan);
  done_at_s_ = t_s + raster->duration_s();
  pen_.restart(std::move(raster), t_s);
  for (auto& h : history_) h.clear();
  best_swing_kPa_ = 0;
  best_ = {};
  return pen_;
}

void SimulatedPulseObserver::feel(const FeltSample& s) {
  if (!s.record || s.t_s > done_at_s_) return;
  constexpr double kBefore_s = 0.3, kAfter_s = 0.15;
  const auto fingers = layout_.centres(s.record->x_mm, s.record->y_mm);
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    auto& h = history_[f];
    h.push_back({s.t_s, s.felt_kPa[f], fingers[f].x_mm, fingers[f].y_mm});
    while (!h.empty() && h.front().t_s < s.t_s - kBefore_s - kAfter_s) h.pop_front();
    if (h.front().t_s > s.t_s - kBefore_s - kAfter_s + 0.01) continue;  // not a full window yet
    // The candidate peak is the sample kAfter_s ago.
    std::size_t centre = h.size() - 1;
    while (centre > 0 && h[centre].t_s > s.t_s - kAfter_s) --centre;
    double left = h[centre].kPa, right = h[centre].kPa;
    for (std::size_t i = 0; i < centre; ++i) left = std::min(left, h[i].kPa);
    for (std::size_t i = centre + 1; i < h.size(); ++i) right = std::min(right, h[i].kPa);
    const double prominence = h[centre].kPa - std::max(left, right);
    if (prominence > best_swing_kPa_) {
      best_swing_kPa_ = prominence;
      best_ = {h[centre].x_mm, h[centre].y_mm};
    }
  }
}

std::optional<Mark> SimulatedPulseObserver::answer(double t_s) {
  if (t_s < done_at_s_ + 1.0) return std::nullopt;
  if (best_swing_kPa_ <= 0) return std::nullopt;  // felt nothing: no mark (the trial times out)
  if (model_.skill.learns() && random_.uniform() >= model_.skill.at(position_)) {
    // A learner who did not recognise the pulse marks somewhere else.
    const double x = bounds_.x0_mm + random_.uniform() * (bounds_.x1_mm - bounds_.x0_mm);
    return Mark{x, bounds_.y0_mm + random_.uniform() * (bounds_.y1_mm - bounds_.y0_mm)};
  }
  return Mark{best_.x_mm + model_.mark_noise_mm * random_.normal(),
              best_.y_mm + model_.mark_noise_mm * random_.normal()};
}

}  // namespace palprig
