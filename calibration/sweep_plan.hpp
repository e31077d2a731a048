#pragma once
// What a calibration sweep commands, as a list of holds (a level held until the regulators
// settle). Paper 002's protocol is the staircase: from 10 to 100 kPa in steps of 10 and back,
// five repeats, each repeat starting vented. For identifying hysteresis, two optional
// excitations add reversals of many sizes (minor loops):
//   random - levels drawn uniformly in [from, to];
//   sine   - levels on a sine whose amplitude shrinks cycle by cycle (nested loops).
// Both are stepped (every level is held until settled) so the fit sees the rate-independent
// hysteresis and not the regulator's lag. For identifying that lag (the regulator's dynamics:
// dead time and first-order lag, calibration/dynamics_fit.hpp), two more excitations are
// recorded sample by sample at the loop's rate (dynamics_rate_hz), each level for a fixed time:
//   step  - steps of many sizes up and down, each held step_hold_s (from vented);
//   chirp - a sine around the middle of the range whose frequency sweeps from chirp_from_hz to
//           chirp_to_hz (logarithmically) over chirp_s.
// Levels above the rig's p_max are clamped to p_max (the backend refuses anything above it)
// and the schedule's notes say so.
#include <string>
#include <vector>

namespace palprig {

enum class SweepSegment { vent, staircase, random, sine, step, chirp };
// Segments recorded sample by sample for the dynamics fit (not averaged into hold points).
bool is_dynamics_segment(SweepSegment s) noexcept;
enum class SweepBranch { none, inflation, deflation };

const char* to_string(SweepSegment s) noexcept;
const char* to_string(SweepBranch b) noexcept;
bool parse_segment(const std::string& text, SweepSegment& out) noexcept;
bool parse_branch(const std::string& text, SweepBranch& out) noexcept;

struct SweepHold {
  SweepSegment segment = SweepSegment::vent;
  int repeat = 0;  // staircase repeat (1-based), 0 elsewhere
  SweepBranch branch = SweepBranch::none;
  double level_kPa = 0;  // the level held; a chirp's centre
  // A timed hold (step and chirp segments): held for this long at the dynamics rate, every
  // sample recorded, no settle test. 0: held until settled (every other segment).
  double duration_s = 0;
  double chirp_amplitude_kPa = 0, chirp_from_hz = 0, chirp_to_hz = 0;
  // The command t_s into the hold (the level; for a chirp the swept sine around it).
  double command_at(double t_s) const noexcept;
};

struct SweepPlanOptions {
  double from_kPa = 10, to_kPa = 100, step_kPa = 10;
  int repeats = 5;
  bool staircase = true;
  bool random = false;
  bool sine = false;
  int random_levels = 60;
  unsigned seed = 1;
  int sine_cycles = 4;
  int sine_steps_per_cycle = 16;
  bool step = false;
  bool chirp = false;
  double step_hold_s = 0.6;  // each step held this long (several regulator time constants)
  double chirp_s = 8.0;
  double chirp_from_hz = 0.5, chirp_to_hz = 12.0;
};

struct SweepSchedule {
  std::vector<SweepHold> holds;
  std::vector<std::string> notes;  // e.g. the p_max clamp
  double p_max_kPa = 0;
};

// Throws InputError("from_kPa", ...) and the like (fields of the options) for arguments that make no sweep.
SweepSchedule plan_calibration_sweep(const SweepPlanOptions& options, double p_max_kPa);

// Why the recording of this schedule could not be fitted (`calibrate fit` would refuse it), said
// before the sweep runs: a staircase branch (inflation or deflation, all repeats together) with
// fewer holds than a line needs (calibration/line_fit.hpp) or with a single level. Empty: long
// enough. A schedule without staircase is not judged here (its fit has no branch lines).
std::string sweep_fit_shortfall(const SweepSchedule& schedule);

}  // namespace palprig
