#pragma once
// The regulator's lag and its compensation: one mechanism for every pressure the tick asks for
// (the pulse, and, when calibration identified the regulators, the whole target; see
// controller/lag_compensation_stage.hpp).
//
// A proportional regulator answers in about 50 ms (paper 002): a dead time, then a first-order
// lag, then its own output slew. The compensator keeps a model y of the regulator's output one
// dead time ahead, and each tick chooses the command u that brings y toward the wanted value
// one tick and one dead time from now (what is wanted then is known ahead: the pulse waveform,
// or the scene where the fingers will be). The fastest move is
//     u = y + (want - y) / alpha,     alpha = 1 - exp(-dt / tau),
// but u is limited to what the rig can do (lo..hi: 0..p_max for a total, and a bound on the lead
// above the target; the command's slew limit, the safety stage's; the regulator's own output
// slew). Because the command can only come back down at its slew rate, the push is the largest
// one from which the slew-limited return still stops y at the wanted level (checked by
// simulating the model, found by bisection): a boost that lands without overshoot, the fastest
// a first-order regulator allows under those limits.
//
// Even so an edge takes time (about 10 ms for 8 kPa on the default rig, longer for a fall that
// the command cannot push below 0 kPa). So that the felt transition is half-way at the true
// edge, the compensator measures how long its model takes to get half-way after a jump in what
// it is asked for, separately for rises and falls, and the stages ask for edges that much
// earlier (anticipation). What one edge measures serves the next.
namespace palprig {

// One channel's regulator as the rig file's plant section describes it.
struct RegulatorLag {
  double dead_time_s = 0.005;
  double time_constant_s = 0.050;
  double slew_kPa_per_s = 2000.0;
  // A regulator that exhausts at another rate than it fills: time_constant_s is then the
  // filling lag and this the exhausting one; 0: one lag both ways.
  double exhaust_time_constant_s = 0.0;
  double exhaust_tau_s() const noexcept {
    return exhaust_time_constant_s > 0 ? exhaust_time_constant_s : time_constant_s;
  }
};

class LagCompensator {
 public:
  // Command for the pulse part. lo..hi bounds the pulse part so that the total stays in
  // 0..p_max; max_step_kPa is the command's slew allowance this tick. dt_s <= 0 (the first
  // tick) passes the wanted value through without advancing the model.
  double command(const RegulatorLag& lag, double want_ahead_kPa, double lo_kPa, double hi_kPa, double max_step_kPa,
                 double dt_s) noexcept;
  double predicted_kPa() const noexcept { return predicted_kPa_; }
  double last_command_kPa() const noexcept { return last_command_kPa_; }
  // Start over from a known output and command (a run that starts or restarts vented: 0, 0; a
  // channel whose compensated quantity changed, e.g. from the pulse part to the whole target).
  // The measured anticipations are kept: they describe the regulator, not its state.
  void reset(double predicted_kPa, double last_command_kPa) noexcept {
    predicted_kPa_ = predicted_kPa;
    last_command_kPa_ = last_command_kPa;
    last_want_kPa_ = predicted_kPa;
    timing_ = false;
  }
  // How early rectangular edges should be asked for (s), as last measured.
  double rise_anticipation_s() const noexcept { return rise_anticipation_s_; }
  double fall_anticipation_s() const noexcept { return fall_anticipation_s_; }

 private:
  void measure_edges(double want, double dt_s) noexcept;

  double predicted_kPa_ = 0;
  double last_command_kPa_ = 0;
  double last_want_kPa_ = 0;
  // An edge being timed: where half-way is, which way, and for how long it has run.
  bool timing_ = false;
  double edge_mid_kPa_ = 0, edge_sign_ = 0, edge_elapsed_s_ = 0;
  double rise_anticipation_s_ = 0, fall_anticipation_s_ = 0;
};

}  // namespace palprig
