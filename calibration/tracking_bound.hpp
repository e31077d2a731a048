#pragma once
// The least RMS(monitor - target) any controller can reach on a regulator, given the targets of a
// whole run in advance: a floor under the fidelity figures (bench/bench_fidelity), so that a miss
// can be told apart from a goal the plant itself forbids.
//
// What bounds it: a regulator can fill as fast as it is told but exhausts at most along its
// exhaust lag. With a command of 0 kPa its pressure decays as exp(-dt / tau), so whatever is
// commanded (every command >= 0), p(t_{k+1}) >= p(t_k) exp(-(t_{k+1} - t_k) / tau). Everything
// else a real controller meets (the dead time, the pen known only up to now, the hysteresis, the
// slew limit, p_max, the lead bound; an exhaust that is slower than its fastest at some
// pressures) is left out, so the figure is a lower bound on the RMS of the regulator's pressure:
// no controller tracks better on such a regulator. It would be reached only by a controller that
// knew the future exactly, on a regulator that filled instantly and always exhausted at that
// rate. It bounds the pressure, not a noisy reading of it (a reading clamped at 0 kPa can score
// below the pressure it reads).
//
// Computed exactly: with z_k = p_k exp((t_k - t_0) / tau) the constraint says z is
// non-decreasing, and the objective sum (p_k - r_k)^2 becomes a weighted isotonic regression of
// z, which the pool-adjacent-violators algorithm solves in one pass (by hand: no library of the
// project's list has it; Boost and Eigen do not). Blocks are kept relative to their first sample
// so that exp(-t / tau) over a long run never underflows a number that matters.
#include <cstdint>
#include <span>
#include <vector>

namespace palprig {

struct TrackingBound {
  double sum_squared_kPa2 = 0;  // the least sum over the counted samples of (pressure - target)^2
  std::size_t samples = 0;      // how many were counted
  double rms_kPa() const noexcept;
};

// One channel: sample times (s, increasing), targets (kPa, >= 0) and whether each sample counts
// (the others take part in the dynamics, not in the sum). exhaust_time_constant_s > 0: the
// fastest exhaust the regulator has. The best pressure at every sample is written to best_kPa
// when it is given (the counted samples' values; the others 0). Throws palprig::Error on
// mismatched lengths, times that do not increase, or a non-finite value.
TrackingBound least_tracking_error(std::span<const double> t_s, std::span<const double> target_kPa,
                                   std::span<const std::uint8_t> counted, double exhaust_time_constant_s,
                                   std::vector<double>* best_kPa = nullptr);

// Several channels pooled: sums and counts added.
TrackingBound pooled(std::span<const TrackingBound> channels) noexcept;

}  // namespace palprig
