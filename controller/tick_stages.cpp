// The tick's stages, in the order tick() calls them (controller/tick.hpp). Each is the code that
// was inline in one 100-line tick() before, moved here unchanged: the demo, sessions and their
// stored figures are byte for byte what they were.
#include <algorithm>
#include <cmath>

#include "controller/tick.hpp"
#include "models/finger_placement.hpp"

namespace palprig {

FingersOnSkin finger_placement_stage(TickState& state, const TickConfig& config, const TouchSample& sample, double t_s,
                                     TelemetryRecord& rec) noexcept {
  FingersOnSkin fingers;
  // Each bad reading is named for what is wrong with it (a NaN position is not a bad force).
  if (!std::isfinite(sample.x_mm) || !std::isfinite(sample.y_mm) || !finger_positions_finite(sample)) {
    state.enter_fault(FaultCode::bad_position);
  } else if (!std::isfinite(sample.t_s)) {
    state.enter_fault(FaultCode::bad_time);
  } else if (!std::isfinite(sample.force_N) || sample.force_N < 0 || !finger_forces_valid(sample)) {
    state.enter_fault(FaultCode::bad_sample);
  } else if (t_s - sample.t_s > config.safety.max_input_age_s) {
    state.enter_fault(FaultCode::input_stale);
  } else {
    // The triangle around the pen, or each finger at its own tracked position; a finger whose
    // tool is out of view is vented (target 0 kPa) and says why in the record.
    const PlacedFingers placed = place_fingers(config.layout, sample, config.contact_force_N);
    fingers.centres = placed.centres;
    fingers.finger_force_N = placed.force_N;
    fingers.finger_pressed = placed.pressed;
    if (sample.own_positions) rec.flags |= kOwnPositions;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      rec.finger_x_mm[i] = static_cast<float>(placed.centres[i].x_mm);
      rec.finger_y_mm[i] = static_cast<float>(placed.centres[i].y_mm);
      rec.finger_force_N[i] = static_cast<float>(placed.force_N[i]);
      rec.finger_vent[i] = sample.fingers[i].vent;
    }
    if (sample.in_contact && sample.force_N >= config.contact_force_N) {
      rec.flags |= kInContact;
      fingers.pressed = true;
      fingers.force_N = sample.force_N;
    }
  }
  if (!fingers.pressed) fingers.force_N = sample.force_N;
  return fingers;
}

void tissue_drag_stage(TickState& state, const Scene& scene, FingersOnSkin& fingers, double dt_s,
                       TelemetryRecord& rec) noexcept {
  // Paper 000's stick/slip: each finger feels the tissue now under it, which a sticking finger
  // has carried along; the arteries move with it too. Each finger drags with its own force (a
  // load cell under each tracked finger); a vented finger carries nothing.
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const bool pressing = fingers.pressed && fingers.finger_pressed[i];
    step_drag(state.drag[i], scene.drag(state.drag_layer[i]), fingers.centres[i], fingers.finger_force_N[i], pressing,
              std::max(dt_s, 0.0));
    if (pressing) fingers.centres[i] = state.drag[i].felt_point(fingers.centres[i]);
    rec.drag_x_mm[i] = static_cast<float>(state.drag[i].offset.x_mm);
    rec.drag_y_mm[i] = static_cast<float>(state.drag[i].offset.y_mm);
  }
}

namespace {

// The target of one finger pressing `felt_at` (the tissue point under it) with force_N: the
// scene's stiffness there, the stress model and the channel's actuator line. A scene rendering
// from the finite-element table gives the stress its nodules add instead: the healthy tissue's
// stress at this press (the stress model's soft stress, which the actuator's passive part
// renders) plus that rise.
double finger_target_kPa(const TickConfig& config, const Scene& scene, std::size_t i, const Point2_mm& felt_at,
                         double force_N, double t_s, TissueSample* felt_out = nullptr) noexcept {
  const TissueSample felt = scene.sample(felt_at, force_N, t_s);
  if (felt_out) *felt_out = felt;
  const double stress_kPa = felt.fe_stress ? config.stress.target_stress_kPa(0.0, force_N) + felt.stress_rise_kPa
                                           : config.stress.target_stress_kPa(felt.stiffness, force_N);
  return config.actuators[i].pressure_kPa(stress_kPa, config.stress.force_ratio(force_N));
}

// Where the fingers will be `lead_s` from now (the pen extrapolated from its past samples),
// which tissue they will press then (the drag stepped along), and the target there.
// Where finger i will press at t_s (the pen extrapolated from its past samples) and how hard;
// false when it will not press (a lift coming, vented, or lifting).
bool predicted_press(const TickState& state, const TickConfig& config, std::size_t i, double t_s, Point2_mm& centre,
                     double& force_N) noexcept {
  const PredictedFinger pen = state.lag.pen.predict_finger(t_s, config.lag_compensation.prediction, i);
  if (!pen.in_contact || !(pen.pen_force_N >= config.contact_force_N)) return false;  // a lift coming
  // The pen's triangle, or (tracked fingers) this finger's own extrapolated position and force,
  // as place_fingers places them now.
  force_N = pen.own_force ? pen.force_N : pen.pen_force_N;
  if (!(force_N >= config.contact_force_N) || pen.vent != FingerVent::none) return false;  // vented, or lifting
  centre = pen.own_position ? Point2_mm{pen.x_mm, pen.y_mm} : config.layout.centres(pen.pen_x_mm, pen.pen_y_mm)[i];
  return true;
}

double predicted_target_kPa(const TickState& state, const TickConfig& config, const Scene& scene, std::size_t i,
                            double t_s, double lead_s) noexcept {
  Point2_mm centre;
  double force_N = 0;
  if (!predicted_press(state, config, i, t_s + lead_s, centre, force_N)) return 0.0;
  const DragSetting setting = scene.drag(state.drag_layer[i]);
  if (!setting.drags() && state.drag[i].phase == DragPhase::free && state.drag[i].offset.x_mm == 0 &&
      state.drag[i].offset.y_mm == 0)
    return finger_target_kPa(config, scene, i, centre, force_N, t_s + lead_s);  // nothing carried
  FingerDrag drag = state.drag[i];
  step_drag(drag, setting, centre, force_N, true, lead_s);
  return finger_target_kPa(config, scene, i, drag.felt_point(centre), force_N, t_s + lead_s);
}

// The target of finger i `ahead_s` from now, for the lag compensation's look ahead.
struct Ahead {
  const TickState& state;
  const TickConfig& config;
  const Scene& scene;
  std::size_t i;
  double t_s, now_kPa;
  static double sample(const void* context, double ahead_s) noexcept {
    const Ahead& a = *static_cast<const Ahead*>(context);
    return ahead_s > 0 ? predicted_target_kPa(a.state, a.config, a.scene, a.i, a.t_s, ahead_s) : a.now_kPa;
  }
};

}  // namespace

void scene_prefetch_stage(const TickState& state, const TickConfig& config, const Scene& scene,
                          const FingersOnSkin& fingers, const LagPlan& plan, double t_s) noexcept {
  if (!scene.prefetch_pays()) return;
  for (std::size_t i = 0; i < kFingerCount; ++i)
    if (fingers.pressed && fingers.finger_pressed[i]) scene.prefetch(fingers.centres[i]);
  if (!plan.any_total() || state.fault != FaultCode::none) return;
  const LagCompensationSetting& lag = config.lag_compensation;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    if (plan.part[i] != CompensatedPart::total || lag.samples_ahead < 1) continue;
    Point2_mm centre;
    double force_N = 0;
    // The sample at the lead, and the window's when this tick takes it afresh (the drag's offset,
    // which moves the felt point a little, is left out of the hint).
    if (predicted_press(state, config, i, t_s + plan.lead_s[i], centre, force_N)) scene.prefetch(centre);
    const bool window_due = !state.lag.window_sampled[i] || state.lag.ticks % kWindowStride == i % kWindowStride;
    if (lag.samples_ahead >= 2 && lag.anticipate_edges && window_due) {
      const double window_s = look_ahead_window_s(plan.model[i], state.lag.compensator[i].predicted_kPa());
      if (window_s > 0 && predicted_press(state, config, i, t_s + plan.lead_s[i] + window_s, centre, force_N))
        scene.prefetch(centre);
    }
  }
}

ChannelPressures stiffness_target_stage(TickState& state, const TickConfig& config, const Scene& scene,
                                        const FingersOnSkin& fingers, double t_s, TelemetryRecord& rec) noexcept {
  ChannelPressures target{};
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    if (!fingers.pressed || !fingers.finger_pressed[i]) {
      state.drag_layer[i] = -1;
      continue;
    }
    TissueSample felt;
    target[i] = finger_target_kPa(config, scene, i, fingers.centres[i], fingers.finger_force_N[i], t_s, &felt);
    rec.stiffness[i] = static_cast<float>(felt.stiffness);
    state.drag_layer[i] = felt.layer;
  }
  return target;
}

void look_ahead_stage(TickState& state, const TickConfig& config, const Scene& scene, const LagPlan& plan,
                      const ChannelPressures& target_now_kPa, double t_s, LagTargets& targets,
                      TelemetryRecord& rec) noexcept {
  if (!plan.any_total() || state.fault != FaultCode::none) return;
  rec.flags |= kLagCompensated;
  // Every channel's samples at the lead and the window first (the prefetch stage asked for
  // them); then the last sample of each channel whose edge needs one, asked for at once, and
  // only then read: they depend on the first samples, so no earlier stage could ask for them.
  const LagCompensationSetting& lag = config.lag_compensation;
  std::array<EdgeAnticipation, kFingerCount> begun{};
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    if (plan.part[i] != CompensatedPart::total) continue;
    const Ahead context{state, config, scene, i, t_s, target_now_kPa[i]};
    const WindowCache window{&state.lag.window_target_kPa[i], &state.lag.window_sampled[i],
                             state.lag.ticks % kWindowStride == i % kWindowStride};
    begun[i] = begin_anticipation(plan.model[i], plan.lead_s[i], state.lag.compensator[i].predicted_kPa(),
                                  lag.max_lead_kPa, config.safety.p_max_kPa, lag.samples_ahead, lag.anticipate_edges,
                                  &Ahead::sample, &context, window);
  }
  if (scene.prefetch_pays())
    for (std::size_t i = 0; i < kFingerCount; ++i)
      if (plan.part[i] == CompensatedPart::total && begun[i].needs_sample()) {
        Point2_mm centre;
        double force_N = 0;
        if (begun[i].there_ahead_s > 0 &&
            predicted_press(state, config, i, t_s + begun[i].there_ahead_s, centre, force_N))
          scene.prefetch(centre);
      }
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    if (plan.part[i] != CompensatedPart::total) continue;
    const EdgeAnticipation& a = begun[i];
    const Ahead context{state, config, scene, i, t_s, target_now_kPa[i]};
    targets.base_ahead_kPa[i] =
        finish_anticipation(a, a.needs_sample() ? Ahead::sample(&context, a.there_ahead_s) : a.there_kPa);
  }
}

ChannelPressures hysteresis_inverse_stage(TickState& state, const ChannelPressures& target_kPa) noexcept {
  ChannelPressures command = target_kPa;
  if (state.fault != FaultCode::none) return command;  // venting: the inverses keep their state
  for (std::size_t i = 0; i < kFingerCount; ++i)
    if (std::isfinite(target_kPa[i]) && !state.hysteresis_model[i].is_identity())
      command[i] = state.hysteresis_model[i].input_for(target_kPa[i]);
  return command;
}

void safety_stage(TickState& state, const TickConfig& config, const ChannelPressures& command_kPa, double t_s,
                  TickResult& out) noexcept {
  TelemetryRecord& rec = out.record;
  const SafetyLimits& lim = config.safety;
  for (double p : command_kPa)
    if (!std::isfinite(p)) state.enter_fault(FaultCode::non_finite_target);  // a broken inverse, too

  if (state.fault != FaultCode::none) {
    // Vent: every channel to 0 kPa at once (no slew limit on the way down to safety).
    out.setpoint_kPa = {};
    rec.flags |= kVented;
  } else {
    // The first tick has no previous time: one nominal period. From the vented state (the
    // state's last setpoint is 0 kPa at the start and after restart_from_vented) the
    // setpoint therefore rises by at most one slew step, whatever the pen pressed on.
    const double dt = state.started ? std::max(t_s - state.last_t_s, 0.0) : config.period_s;
    const double max_step = lim.slew_kPa_per_s * dt;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      double p = command_kPa[i];
      if (p > lim.p_max_kPa) {
        p = lim.p_max_kPa;
        rec.flags |= kClamped;
      }
      if (p < 0) p = 0;
      const double prev = state.last_setpoint_kPa[i];
      if (p > prev + max_step) {
        p = prev + max_step;
        rec.flags |= kSlewLimited;
      } else if (p < prev - max_step) {
        p = prev - max_step;
        rec.flags |= kSlewLimited;
      }
      out.setpoint_kPa[i] = p;
    }
  }
  for (std::size_t i = 0; i < kFingerCount; ++i) rec.setpoint_kPa[i] = static_cast<float>(out.setpoint_kPa[i]);
  rec.fault = state.fault;
  rec.t_s = t_s;
  rec.tick = state.ticks++;
  state.last_setpoint_kPa = out.setpoint_kPa;
  state.last_t_s = t_s;
  state.started = true;
}

// The actuator's play follows the setpoints actually sent (not what the inverse stage computed:
// the safety stage may have cut a reversal's jump of twice the play to its slew step, or clamped
// at p_max), with the regulator's exhaust near 0 kPa (the band above the command narrows to the
// command), so the next inversion starts from where the actuator is. Venting: kept as they are.
void hysteresis_follow_setpoints(TickState& state, const TickResult& out) noexcept {
  if (state.fault != FaultCode::none || (out.record.flags & kVented)) return;
  for (std::size_t i = 0; i < kFingerCount; ++i)
    if (!state.hysteresis_model[i].is_identity()) state.hysteresis_model[i].apply_exhausting(out.setpoint_kPa[i]);
}

}  // namespace palprig
