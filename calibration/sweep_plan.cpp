#include "calibration/sweep_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include "calibration/line_fit.hpp"
#include "core/input_error.hpp"

namespace palprig {

const char* to_string(SweepSegment s) noexcept {
  switch (s) {
    case SweepSegment::vent: return "vent";
    case SweepSegment::staircase: return "staircase";
    case SweepSegment::random: return "random";
    case SweepSegment::sine: return "sine";
    case SweepSegment::step: return "step";
    case SweepSegment::chirp: return "chirp";
  }
  return "?";
}

bool is_dynamics_segment(SweepSegment s) noexcept { return s == SweepSegment::step || s == SweepSegment::chirp; }

double SweepHold::command_at(double t_s) const noexcept {
  if (segment != SweepSegment::chirp || !(duration_s > 0) || !(chirp_from_hz > 0) || !(chirp_to_hz > chirp_from_hz))
    return level_kPa;
  // Logarithmic sweep: the phase of f(t) = f0 (f1 / f0)^(t / T), starting at the centre and rising.
  const double t = std::clamp(t_s, 0.0, duration_s);
  const double k = std::log(chirp_to_hz / chirp_from_hz) / duration_s;
  const double phase = 2 * std::numbers::pi * chirp_from_hz * std::expm1(k * t) / k;
  return level_kPa + chirp_amplitude_kPa * std::sin(phase);
}

const char* to_string(SweepBranch b) noexcept {
  switch (b) {
    case SweepBranch::none: return "none";
    case SweepBranch::inflation: return "inflation";
    case SweepBranch::deflation: return "deflation";
  }
  return "?";
}

bool parse_segment(const std::string& t, SweepSegment& out) noexcept {
  for (auto s : {SweepSegment::vent, SweepSegment::staircase, SweepSegment::random, SweepSegment::sine,
                 SweepSegment::step, SweepSegment::chirp})
    if (t == to_string(s)) {
      out = s;
      return true;
    }
  return false;
}

bool parse_branch(const std::string& t, SweepBranch& out) noexcept {
  for (auto b : {SweepBranch::none, SweepBranch::inflation, SweepBranch::deflation})
    if (t == to_string(b)) {
      out = b;
      return true;
    }
  return false;
}

namespace {

std::string kPa_text(double v) {
  std::ostringstream s;
  s << v << " kPa";
  return s.str();
}

}  // namespace

SweepSchedule plan_calibration_sweep(const SweepPlanOptions& o, double p_max_kPa) {
  auto need = [](bool ok, const char* option, const std::string& expected) {
    if (!ok) throw InputError(option, "value", expected);
  };
  need(std::isfinite(o.from_kPa) && o.from_kPa >= 0, "from_kPa", "a pressure >= 0 kPa");
  need(std::isfinite(o.to_kPa) && o.to_kPa > o.from_kPa, "to_kPa", "a pressure above `from_kPa`");
  need(std::isfinite(o.step_kPa) && o.step_kPa > 0, "step_kPa", "a step > 0 kPa");
  need((o.to_kPa - o.from_kPa) / o.step_kPa <= 1000, "step_kPa", "at most 1000 levels between `from_kPa` and `to_kPa`");
  need(o.repeats >= 1 && o.repeats <= 100, "repeats", "1 to 100 repeats");
  need(o.staircase || o.random || o.sine || o.step || o.chirp, "excitation",
       "at least one of staircase, random, sine, step, chirp");
  need(std::isfinite(o.step_hold_s) && o.step_hold_s >= 0.05 && o.step_hold_s <= 60, "step_hold_s",
       "a step hold of 0.05 to 60 s");
  need(std::isfinite(o.chirp_s) && o.chirp_s >= 0.5 && o.chirp_s <= 600, "chirp_s", "a chirp of 0.5 to 600 s");
  need(std::isfinite(o.chirp_from_hz) && o.chirp_from_hz > 0 && std::isfinite(o.chirp_to_hz) &&
           o.chirp_to_hz > o.chirp_from_hz && o.chirp_to_hz <= 100,
       "chirp_to_hz", "a chirp from a frequency > 0 to a higher one, at most 100 Hz");
  need(o.random_levels >= 2 && o.random_levels <= 100000, "random_levels", "2 to 100000 levels");
  need(o.sine_cycles >= 1 && o.sine_cycles <= 1000, "sine_cycles", "1 to 1000 cycles");
  need(o.sine_steps_per_cycle >= 4 && o.sine_steps_per_cycle <= 1000, "sine_steps_per_cycle",
       "4 to 1000 steps per cycle");
  need(p_max_kPa > 0, "rig", "a positive p_max");
  need(o.from_kPa < p_max_kPa, "from_kPa",
       "a level below the rig's p_max (" + kPa_text(p_max_kPa) + "), got " + kPa_text(o.from_kPa));

  SweepSchedule plan;
  plan.p_max_kPa = p_max_kPa;
  const double top = std::min(o.to_kPa, p_max_kPa);
  if (o.to_kPa > p_max_kPa) {
    std::ostringstream s;
    s << "the rig's p_max is " << p_max_kPa << " kPa: sweep levels above it are clamped to " << p_max_kPa
      << " kPa (asked up to " << o.to_kPa << " kPa)";
    plan.notes.push_back(s.str());
  }

  // Staircase levels from..to in steps, clamped, without repeated levels.
  std::vector<double> levels;
  const auto steps = static_cast<int>(std::floor((o.to_kPa - o.from_kPa) / o.step_kPa + 1e-9));
  for (int k = 0; k <= steps; ++k) {
    const double level = std::min(o.from_kPa + k * o.step_kPa, top);
    if (levels.empty() || level > levels.back() + 1e-9) levels.push_back(level);
  }
  if (levels.back() < top - 1e-9) levels.push_back(top);  // the step did not land on `to`

  auto add = [&](SweepSegment seg, int repeat, SweepBranch branch, double level) {
    SweepHold h;
    h.segment = seg;
    h.repeat = repeat;
    h.branch = branch;
    h.level_kPa = level;
    plan.holds.push_back(h);
  };
  if (o.staircase) {
    for (int r = 1; r <= o.repeats; ++r) {
      add(SweepSegment::vent, 0, SweepBranch::none, 0.0);  // every repeat starts vented (paper 002)
      for (double l : levels) add(SweepSegment::staircase, r, SweepBranch::inflation, l);
      for (auto it = levels.rbegin(); it != levels.rend(); ++it)
        add(SweepSegment::staircase, r, SweepBranch::deflation, *it);
    }
  }
  if (o.random) {
    add(SweepSegment::vent, 0, SweepBranch::none, 0.0);
    std::mt19937_64 rng(o.seed);
    std::uniform_real_distribution<double> level(o.from_kPa, top);
    for (int k = 0; k < o.random_levels; ++k) add(SweepSegment::random, 0, SweepBranch::none, level(rng));
  }
  if (o.sine) {
    add(SweepSegment::vent, 0, SweepBranch::none, 0.0);
    const double centre = 0.5 * (o.from_kPa + top), full = 0.5 * (top - o.from_kPa);
    const int total = o.sine_cycles * o.sine_steps_per_cycle;
    for (int k = 0; k <= total; ++k) {
      const double phase = double(k) / o.sine_steps_per_cycle;  // in cycles
      // Amplitude shrinks linearly to a quarter: every cycle's loop nests inside the last.
      const double amplitude = full * (1.0 - 0.75 * phase / o.sine_cycles);
      add(SweepSegment::sine, 0, SweepBranch::none, centre - amplitude * std::cos(2 * std::numbers::pi * phase));
    }
  }
  if (o.step) {
    // Steps up and down of many sizes between from and the top, from vented, and three falls
    // to 0 kPa (from high, low and middle levels): commanded 0 kPa a regulator opens its exhaust,
    // and its last kilopascals empty slowest (the dynamics fit's stage 4,
    // calibration/exhaust_lag_fit.hpp). The tick commands 0 kPa on every fall it anticipates,
    // so that is the lag it must know; without these steps the fit extrapolated it from the
    // lowest level (from_kPa) and missed an exhaust that slows only below it.
    add(SweepSegment::vent, 0, SweepBranch::none, 0.0);
    constexpr double kToZero = -1;  // a step to 0 kPa rather than to a level of the range
    for (double f : {0.2, 0.5, 0.35, 0.8, kToZero, 0.1, kToZero, 0.65, 0.25, 0.95, 0.5, 0.0, 0.4, kToZero}) {
      add(SweepSegment::step, 0, SweepBranch::none, f == kToZero ? 0.0 : o.from_kPa + f * (top - o.from_kPa));
      plan.holds.back().duration_s = o.step_hold_s;
    }
  }
  if (o.chirp) {
    // Around the middle of the range, a quarter of it either way; it starts at the centre, so
    // it follows the steps (or a vent) with one step.
    const double centre = 0.5 * (o.from_kPa + top);
    if (!o.step) add(SweepSegment::vent, 0, SweepBranch::none, 0.0);
    add(SweepSegment::chirp, 0, SweepBranch::none, centre);
    SweepHold& c = plan.holds.back();
    c.duration_s = o.chirp_s;
    c.chirp_amplitude_kPa = 0.25 * (top - o.from_kPa);
    c.chirp_from_hz = o.chirp_from_hz;
    c.chirp_to_hz = o.chirp_to_hz;
  }
  add(SweepSegment::vent, 0, SweepBranch::none, 0.0);
  return plan;
}

std::string sweep_fit_shortfall(const SweepSchedule& schedule) {
  struct Branch {
    std::size_t holds = 0;
    double lo = 0, hi = 0;
  };
  Branch up, down;
  bool staircase = false;
  for (const SweepHold& h : schedule.holds) {
    if (h.segment != SweepSegment::staircase || h.branch == SweepBranch::none) continue;
    staircase = true;
    Branch& b = h.branch == SweepBranch::inflation ? up : down;
    b.lo = b.holds ? std::min(b.lo, h.level_kPa) : h.level_kPa;
    b.hi = b.holds ? std::max(b.hi, h.level_kPa) : h.level_kPa;
    ++b.holds;
  }
  if (!staircase) return {};
  for (const auto& [name, b] : {std::pair<const char*, const Branch&>{"inflation", up}, {"deflation", down}}) {
    std::ostringstream why;
    if (b.holds < kMinLinePoints)
      why << "too short to fit: the " << name << " staircase has " << b.holds << " hold" << (b.holds == 1 ? "" : "s")
          << " over all repeats and a line needs " << kMinLinePoints << " (lower Step, widen From/To or add repeats)";
    else if (!(b.hi > b.lo))
      why << "too short to fit: the " << name << " staircase holds one level only (" << b.lo
          << " kPa) and a line needs two (lower Step or widen From/To)";
    if (!why.str().empty()) return why.str();
  }
  return {};
}

}  // namespace palprig
