#include "controller/lag_compensation_stage.hpp"

#include <algorithm>
#include <cmath>

namespace palprig {

LagPlan plan_lag_compensation(const LagCompensationState& state, const LagCompensationSetting& setting,
                              const std::array<RegulatorLag, kFingerCount>& pulse_lag, bool pulse_compensation, bool on,
                              bool has_pulse, double period_s) noexcept {
  LagPlan plan;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    // The identified model where calibration has one that fits, else the rig file's plant.
    plan.model[i] = setting.identified[i] ? setting.regulator[i] : pulse_lag[i];
    plan.part[i] = CompensatedPart::none;  // switched off, or nothing to compensate
    if (on && setting.whole(i))
      plan.part[i] = CompensatedPart::total;
    else if (on && has_pulse && pulse_compensation)
      plan.part[i] = CompensatedPart::pulse;
    if (plan.part[i] == CompensatedPart::none) continue;
    // A command issued now reaches the regulator one tick later and acts a dead time after that.
    plan.lead_s[i] = plan.model[i].dead_time_s + period_s;
    // The measured half-way times of the channel's compensator, when it stands for the same part
    // (what it measured on the pulse alone does not time the whole target's edges).
    if (state.part[i] == plan.part[i] && (plan.part[i] == CompensatedPart::pulse || setting.anticipate_edges)) {
      plan.rise_advance_s[i] = state.compensator[i].rise_anticipation_s();
      plan.fall_advance_s[i] = state.compensator[i].fall_anticipation_s();
    }
  }
  return plan;
}

double look_ahead_window_s(const RegulatorLag& model, double y_kPa) noexcept {
  constexpr double kLn2 = 0.6931471805599453;
  const double y = std::max(y_kPa, 0.0);
  // The half-life: a whole fall's half-way time (the slower lag's, so both edges are seen); an
  // exhaust that slows near 0 kPa takes longer to halve a low pressure than a high one.
  const double fall_half_life_s =
      model.exhaust_depends_on_pressure() && y > 0 ? model.exhaust_time_s(y, 0.5 * y) : model.exhaust_tau_s() * kLn2;
  return std::max(model.time_constant_s * kLn2, fall_half_life_s);
}

EdgeAnticipation begin_anticipation(const RegulatorLag& model, double lead_s, double y_kPa, double max_lead_kPa,
                                    double p_max_kPa, int samples_ahead, bool anticipate, TargetAhead sample,
                                    const void* context, const WindowCache& window) noexcept {
  EdgeAnticipation out;
  if (samples_ahead < 1) {
    out.at_lead_kPa = sample(context, 0.0);
    return out;
  }
  const double at_lead = sample(context, lead_s);
  out.at_lead_kPa = at_lead;
  // A rise goes at the filling lag, a fall at the exhausting one (the same for one lag).
  const double tau = model.time_constant_s, tau_fall = model.exhaust_tau_s();
  if (!anticipate || samples_ahead < 2 || !(tau > 0) || !(tau_fall > 0) || !std::isfinite(at_lead) ||
      !std::isfinite(y_kPa))
    return out;
  constexpr double kEdge_kPa = 0.25;  // smaller changes are followed as they come
  const double y = std::max(y_kPa, 0.0);
  const double window_s = look_ahead_window_s(model, y);
  double later;
  if (window.target_kPa && window.sampled && *window.sampled && !window.fresh) {
    later = *window.target_kPa;
  } else {
    later = sample(context, lead_s + window_s);
    if (window.target_kPa && window.sampled) *window.target_kPa = later, *window.sampled = true;
  }
  if (!std::isfinite(later)) return out;
  if (later < at_lead - kEdge_kPa && later < y) {
    const double b = std::max(later, 0.0);
    const double half_way_s = y > 0 ? std::clamp(model.exhaust_time_s(y, 0.5 * (y + b)), 0.0, window_s) : 0.0;
    out.edge = EdgeAnticipation::Edge::fall;
    out.sample_needed = samples_ahead >= 3;
    if (out.sample_needed)
      out.there_ahead_s = lead_s + half_way_s;
    else
      out.there_kPa = later;
    return out;
  }
  if (later > at_lead + kEdge_kPa && later > y) {
    const double b = later;
    const double hi = std::min(p_max_kPa, b + std::min(max_lead_kPa, b));
    const double mid = 0.5 * (y + b);
    if (!(hi > mid)) return out;
    const double half_way_s = std::clamp(tau * std::log((hi - y) / (hi - mid)), 0.0, window_s);
    out.edge = EdgeAnticipation::Edge::rise;
    out.sample_needed = samples_ahead >= 3;
    if (out.sample_needed)
      out.there_ahead_s = lead_s + half_way_s;
    else
      out.there_kPa = at_lead;
  }
  return out;
}

double finish_anticipation(const EdgeAnticipation& a, double there_kPa) noexcept {
  const double at_lead = a.at_lead_kPa;
  switch (a.edge) {
    case EdgeAnticipation::Edge::none: return at_lead;
    case EdgeAnticipation::Edge::fall: return std::isfinite(there_kPa) ? std::min(at_lead, there_kPa) : at_lead;
    case EdgeAnticipation::Edge::rise: return std::isfinite(there_kPa) ? std::max(at_lead, there_kPa) : at_lead;
  }
  return at_lead;
}

double anticipated_target_kPa(const RegulatorLag& model, double lead_s, double y_kPa, double max_lead_kPa,
                              double p_max_kPa, int samples_ahead, bool anticipate, TargetAhead sample,
                              const void* context, const WindowCache& window) noexcept {
  const EdgeAnticipation a = begin_anticipation(model, lead_s, y_kPa, max_lead_kPa, p_max_kPa, samples_ahead,
                                                anticipate, sample, context, window);
  return finish_anticipation(a, a.needs_sample() ? sample(context, a.there_ahead_s) : a.there_kPa);
}

ChannelPressures lag_compensation_stage(LagCompensationState& state, const LagPlan& plan, const LagTargets& in,
                                        const LagLimits& limits, double dt_s) noexcept {
  ChannelPressures command{};
  const bool stepped = dt_s > 0 && std::isfinite(dt_s);
  const double max_step = stepped ? limits.slew_kPa_per_s * dt_s : 0.0;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const double base = in.base_now_kPa[i];
    const double now = base + in.pulse_now_kPa[i];
    LagCompensator& c = state.compensator[i];
    const CompensatedPart part = plan.part[i];
    if (part != state.part[i] && stepped) {
      // The compensator now stands for another part of the command: carry its model over to
      // the new part (the regulator's output does not jump because its command's meaning did).
      double y = c.predicted_kPa(), u = c.last_command_kPa();
      if (state.part[i] == CompensatedPart::pulse && part == CompensatedPart::total)
        y += base, u += base;
      else if (state.part[i] == CompensatedPart::total && part == CompensatedPart::pulse)
        y -= base, u -= base;
      else if (part == CompensatedPart::total)
        y = u = now;
      else
        y = u = in.pulse_now_kPa[i];
      c.reset(y, u);
    }
    state.part[i] = part;
    if (!std::isfinite(base)) {
      command[i] = base;  // left for the safety stage to fault on
      continue;
    }
    switch (part) {
      case CompensatedPart::none: command[i] = now; break;
      case CompensatedPart::pulse: {
        // The pulse part may dip below zero (to speed a fall) but never takes the total below
        // 0 kPa or above p_max.
        const double lo = -std::max(base, 0.0);
        const double hi = std::max(limits.p_max_kPa - base, 0.0);
        command[i] = base + c.command(plan.model[i], in.pulse_ahead_kPa[i], lo, hi, max_step, stepped ? dt_s : 0.0);
        break;
      }
      case CompensatedPart::total: {
        const double want = in.base_ahead_kPa[i] + in.pulse_ahead_kPa[i];
        // The lead bound: no command more than max_lead_kPa above what the models ask for now or
        // ahead, nor more than twice that (a light target near the regulator's exhaust gets a
        // light push), whatever the regulator model says; and never above p_max.
        const double ceiling = std::max(std::isfinite(want) ? std::max(now, want) : now, 0.0);
        const double hi = std::clamp(ceiling + std::min(limits.max_lead_kPa, ceiling), 0.0, limits.p_max_kPa);
        command[i] =
            c.command(plan.model[i], std::isfinite(want) ? want : now, 0.0, hi, max_step, stepped ? dt_s : 0.0);
        break;
      }
    }
  }
  return command;
}

}  // namespace palprig
