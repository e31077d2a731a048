#pragma once
// The rig's safety limits (rig file "safety" section): read by the tick's safety stage and,
// for p_max, again at every backend boundary. Plain data, so config readers need not include
// the tick.
namespace palprig {

struct SafetyLimits {
  double p_max_kPa = 60.0;         // no setpoint above this ever leaves the tick
  double slew_kPa_per_s = 2000.0;  // largest setpoint change per second (venting is exempt)
  double max_input_age_s = 0.1;    // older pen samples fault the loop (input_stale)
  int max_consecutive_overruns = 20;
  // Periods the loop did not run (skipped after overruns, or beyond the period in a replay's
  // CPU time) add up to its lost time, which drains by 1 % of the time run; beyond this the
  // loop cannot hold its rate and faults (lost_time_limit). 50 ms: the regulator's time
  // constant, the longest the rig may go uncontrolled.
  double max_lost_time_s = 0.05;
};

}  // namespace palprig
