#pragma once
// The tick's lag compensation stage (docs/architecture.md, "The tick": between the target and the
// hysteresis inverse). The regulators answer a dead time and a first-order lag late (paper 002:
// about 50 ms), so a fingertip crossing a tumor edge feels it a lag late and a pulse arrives
// late and rounded. One mechanism for both: per channel a LagCompensator
// (models/lag_compensator.hpp) commands the inverse of the regulator's dynamics (a phase lead)
// toward what is wanted one dead time and one tick ahead:
//
//   - whole target (calibration identified the channel's dynamics with a good fit, and lag
//     compensation is switched on: the calibration file's `lag_compensation.enabled` or
//     `--compensate-lag`): what is wanted ahead is the scene sampled where the fingers will be
//     (PenPredictor: position, velocity and force extrapolated from past pen samples only, over
//     the channel's dead time plus one tick, and a little further for edges the regulator needs
//     longer for), plus the pulse read ahead. The command stays within [0, p_max] and the safety
//     stage's slew step, and at most max_lead_kPa above the larger of the target now and the
//     target ahead: a wrong model can push no harder than that.
//   - pulse part only (the default for scenes with arteries): the stiffness part passes as the
//     tick computed it, and the compensator works on the pulse alone, the total kept in
//     [0, p_max] (what the pulse stage did on its own before).
//   - nothing: the target passes unchanged.
//
// The regulator model of a channel is calibration's identified one when it is usable, else the
// rig file's plant section (for the pulse). The stage runs on the loop thread: fixed-size state,
// no allocation, no locks, no exceptions. It includes nothing of the tick.
#include <array>
#include <atomic>
#include <cstdint>

#include "models/channel_pressures.hpp"
#include "models/finger_layout.hpp"
#include "models/lag_compensator.hpp"
#include "models/pen_predictor.hpp"

namespace palprig {

// The setting calibration gives (controller/tick_setup.cpp fills it from the calibration file).
struct LagCompensationSetting {
  bool whole_target = false;                           // switched on for the whole target
  std::array<bool, kFingerCount> identified{};         // the channel's dynamics were identified with a good fit
  std::array<RegulatorLag, kFingerCount> regulator{};  // the identified models
  double max_lead_kPa = 10.0;                          // the command's lead above the target, at most
  bool anticipate_edges = true;                        // ask for edges the regulator takes time over earlier
  // How many times per finger and tick the scene may be sampled ahead (the target one lead
  // ahead, then up to two more for the edges): 3, or fewer where a function scene's sampling is
  // too costly for a tick (controller/run_setup.cpp); 0 compensates toward the target now.
  int samples_ahead = 3;
  PenPrediction prediction;
  // Whether channel i compensates its whole target.
  bool whole(std::size_t i) const noexcept { return whole_target && identified[i]; }
};

// What each channel's compensator stands for.
enum class CompensatedPart : std::uint8_t { none, pulse, total };

// Kept between ticks in the tick state (fixed size).
struct LagCompensationState {
  std::array<LagCompensator, kFingerCount> compensator{};
  std::array<CompensatedPart, kFingerCount> part{};
  PenPredictor pen;
  // The target one half-life beyond the lead, per finger, as last sampled: it only says whether
  // an edge lies within the window, so it is sampled every kWindowStride ticks (one finger a
  // tick), not every tick.
  std::array<double, kFingerCount> window_target_kPa{};
  std::array<bool, kFingerCount> window_sampled{};
  std::uint64_t ticks = 0;
  // The channels were vented: every model output and command is 0 kPa again.
  void restart_from_vented() noexcept {
    for (auto& c : compensator) c.reset(0.0, 0.0);
    window_sampled = {};
  }
};

// What each channel does this tick, decided before the scene is sampled ahead and the pulse read.
struct LagPlan {
  std::array<CompensatedPart, kFingerCount> part{};
  std::array<RegulatorLag, kFingerCount> model{};
  // How far ahead each channel reads what it wants, and how much earlier it asks for rising and
  // falling edges (its compensator's measured half-way times; 0 without compensation).
  std::array<double, kFingerCount> lead_s{}, rise_advance_s{}, fall_advance_s{};
  bool any_total() const noexcept {
    for (CompensatedPart p : part)
      if (p == CompensatedPart::total) return true;
    return false;
  }
};

// The plan: `on` is the run-time switch (the window's check box; true without one), pulse_lag
// the rig file's regulators, has_pulse whether the scene has arteries, period_s the time the
// command takes to reach the regulator (one tick).
LagPlan plan_lag_compensation(const LagCompensationState& state, const LagCompensationSetting& setting,
                              const std::array<RegulatorLag, kFingerCount>& pulse_lag, bool pulse_compensation, bool on,
                              bool has_pulse, double period_s) noexcept;

// Edges the regulator takes time over, asked for earlier so that the regulator's output is
// half-way at the edge (the least squared error for a step). `sample(context, s)` is the target
// s seconds from now (the scene where the fingers will be); y the compensator's model output
// (where the regulator is heading one dead time ahead). A fall can only let the output decay
// (0 kPa commanded): its half-way time from y to the level B it falls to is tau ln(2y / (y + B))
// (tau: the exhausting lag for a fall, the filling one for a rise, where they differ; an
// exhausting lag that grows near 0 kPa integrated over the way down: RegulatorLag::exhaust_time_s),
// at most the half-life (a whole fall's from y), the window looked into for B; a rise is pushed with the command
// at its bound hi (at most max_lead_kPa above B, and at most twice B): tau ln((hi - y) / (hi -
// (y + B) / 2)). With an edge in the window, what is asked for is the target that half-way time
// ahead (a single step is then half-way at its edge, and along a staircase the time looked at
// only moves forward, so the command does not turn back and forth). Uses at most samples_ahead
// samples (the one at the lead included); 0: the target now.
// window_kPa, when given, caches the target one half-life beyond the lead between ticks:
// resampled when fresh is true or it holds none (window_sampled false), reused otherwise.
using TargetAhead = double (*)(const void* context, double ahead_s);
inline constexpr std::uint64_t kWindowStride = 3;
struct WindowCache {
  double* target_kPa = nullptr;
  bool* sampled = nullptr;
  bool fresh = true;
};
// The window anticipated_target_kPa looks into beyond the lead: the half-life of a whole fall
// from y_kPa (or of a rise, if the filling lag is the slower).
double look_ahead_window_s(const RegulatorLag& model, double y_kPa) noexcept;
double anticipated_target_kPa(const RegulatorLag& model, double lead_s, double y_kPa, double max_lead_kPa,
                              double p_max_kPa, int samples_ahead, bool anticipate, TargetAhead sample,
                              const void* context, const WindowCache& window = {}) noexcept;

// anticipated_target_kPa in two halves, so that a caller with several channels can ask for every
// channel's last sample at once before reading any (the tick prefetches them: on a map larger
// than the cache each is a miss, and one after another they queue): begin_anticipation takes the
// samples at the lead and the window and says whether an edge needs one more, `there_ahead_s`
// from now; finish_anticipation combines that sample (or there_kPa, when none was needed) with
// the one at the lead. anticipated_target_kPa is exactly the two in a row.
struct EdgeAnticipation {
  enum class Edge { none, fall, rise } edge = Edge::none;
  double at_lead_kPa = 0.0;
  bool sample_needed = false;  // finish_anticipation needs the target there_ahead_s from now
  double there_ahead_s = 0.0;
  double there_kPa = 0.0;  // the value to finish with when no sample is needed
  bool needs_sample() const noexcept { return sample_needed; }
};
EdgeAnticipation begin_anticipation(const RegulatorLag& model, double lead_s, double y_kPa, double max_lead_kPa,
                                    double p_max_kPa, int samples_ahead, bool anticipate, TargetAhead sample,
                                    const void* context, const WindowCache& window = {}) noexcept;
double finish_anticipation(const EdgeAnticipation& a, double there_kPa) noexcept;

// The targets the stage works from: the stiffness part now and ahead (ahead only for channels
// compensating the total; the stage ignores it elsewhere), and the pulse now and ahead.
struct LagTargets {
  ChannelPressures base_now_kPa{}, base_ahead_kPa{};
  ChannelPressures pulse_now_kPa{}, pulse_ahead_kPa{};
};

struct LagLimits {
  double p_max_kPa = 60;
  double slew_kPa_per_s = 2000;  // the safety stage's
  double max_lead_kPa = 10;
};

// The commands (before the hysteresis inverse). dt_s: time since the last tick (0 on the first).
// Non-finite targets pass through for the safety stage to fault on.
ChannelPressures lag_compensation_stage(LagCompensationState& state, const LagPlan& plan, const LagTargets& targets,
                                        const LagLimits& limits, double dt_s) noexcept;

}  // namespace palprig
