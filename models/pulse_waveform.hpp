#pragma once
// Pulse waveforms and the pulse clock.
//
// A waveform is one heartbeat's shape over phase 0..1, valued 0..1:
//   rectangular  1 while phase < duty, else 0 (papers 000, 004: D = 0.2 by default);
//   saw-tooth    rises linearly to 1 over rise_fraction, then falls linearly to 0 at the end of
//                the beat (paper 003's approximation of the arterial pressure wave);
//   table        a lookup table resampled from one recorded beat (paper 004), normalised so
//                its minimum is 0 and its maximum 1.
//
// PulseClock turns time into phase from timestamps, not tick counts (paper 004): the phase at
// time t is anchor_phase + (t - anchor_t) * bpm / 60, so the rate is exact whatever the loop
// rate or its jitter. A rate change re-anchors at the time it takes effect, keeping the phase
// continuous (no jump or missed beat when the rate changes while running).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace palprig {

inline constexpr double kMinPulseRateBpm = 20.0;  // refused outside this range
inline constexpr double kMaxPulseRateBpm = 250.0;

enum class WaveShape : std::uint8_t { rectangular, sawtooth, table };

class PulseWaveform {
 public:
  static constexpr std::size_t kTableSize = 512;

  PulseWaveform() = default;  // rectangular, duty 0.2
  // The factories throw BadInput naming what is wrong.
  static PulseWaveform rectangular(double duty = 0.2);
  static PulseWaveform sawtooth(double rise_fraction = 0.15);
  // One recorded beat: times strictly increasing, the last sample closing the cycle (its value
  // back at the first's within 5 % of the range: a table that does not return is not periodic).
  static PulseWaveform table(const std::vector<double>& t_s, const std::vector<double>& value);

  // Value at a phase in cycles (any real; only the fractional part counts).
  double value(double phase) const noexcept;
  // The same with the rectangular wave's rising edge moved earlier by rise_advance and its
  // falling edge by fall_advance (cycles, each 0 .. < duty), so a slow actuator can start each
  // transition early enough to be half-way at the true edge. Other shapes are smooth enough to
  // track and ignore the advances.
  double value_advanced(double phase, double rise_advance, double fall_advance) const noexcept;
  bool has_edges() const noexcept { return shape_ == WaveShape::rectangular; }
  WaveShape shape() const noexcept { return shape_; }
  double duty() const noexcept { return param_; }           // rectangular
  double rise_fraction() const noexcept { return param_; }  // saw-tooth
  // The table waveform's source beat length (informative only: the rate sets the period).
  double recorded_period_s() const noexcept { return recorded_period_s_; }

 private:
  WaveShape shape_ = WaveShape::rectangular;
  double param_ = 0.2;
  double recorded_period_s_ = 0;
  std::array<float, kTableSize + 1> table_{};  // +1: the closing sample, equal to the first
};

struct PulseClock {
  double bpm = 72.0;
  double anchor_t_s = 0.0;
  double anchor_phase = 0.0;  // cycles

  double phase(double t_s) const noexcept { return anchor_phase + (t_s - anchor_t_s) * bpm / 60.0; }
  // From t_s on, beat at bpm (phase continuous at t_s).
  void change_rate(double new_bpm, double t_s) noexcept {
    anchor_phase = phase(t_s);
    anchor_t_s = t_s;
    bpm = new_bpm;
  }
};

}  // namespace palprig
