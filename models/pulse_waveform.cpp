#include "models/pulse_waveform.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.hpp"

namespace palprig {

namespace {
void need_waveform(bool ok, const std::string& what) {
  if (!ok) throw BadInput(what);
}
}  // namespace

PulseWaveform PulseWaveform::rectangular(double duty) {
  need_waveform(std::isfinite(duty) && duty > 0 && duty < 1, "duty cycle must lie strictly between 0 and 1");
  PulseWaveform w;
  w.shape_ = WaveShape::rectangular;
  w.param_ = duty;
  return w;
}

PulseWaveform PulseWaveform::sawtooth(double rise_fraction) {
  need_waveform(std::isfinite(rise_fraction) && rise_fraction > 0 && rise_fraction < 1,
                "saw-tooth rise fraction must lie strictly between 0 and 1");
  PulseWaveform w;
  w.shape_ = WaveShape::sawtooth;
  w.param_ = rise_fraction;
  return w;
}

PulseWaveform PulseWaveform::table(const std::vector<double>& t_s, const std::vector<double>& value) {
  need_waveform(!t_s.empty() && t_s.size() == value.size(), "waveform table is empty");
  need_waveform(t_s.size() >= 4,
                "waveform table needs at least 4 samples over one beat, got " + std::to_string(t_s.size()));
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    need_waveform(std::isfinite(t_s[i]) && std::isfinite(value[i]),
                  "waveform table row " + std::to_string(i + 1) + " is not finite");
    if (i > 0)
      need_waveform(t_s[i] > t_s[i - 1],
                    "waveform table times must increase strictly (row " + std::to_string(i + 1) + ")");
  }
  const auto [lo_it, hi_it] = std::minmax_element(value.begin(), value.end());
  const double lo = *lo_it, hi = *hi_it, range = hi - lo;
  need_waveform(range > 0, "waveform table is flat (no pulse in it)");
  need_waveform(
      std::abs(value.back() - value.front()) <= 0.05 * range,
      "waveform table is not periodic: its last value must return to its first (within 5 % of the range) to close "
      "the beat");
  PulseWaveform w;
  w.shape_ = WaveShape::table;
  w.param_ = 0;
  const double t0 = t_s.front(), period = t_s.back() - t0;
  w.recorded_period_s_ = period;
  std::size_t j = 0;
  for (std::size_t i = 0; i <= kTableSize; ++i) {
    const double t = t0 + period * static_cast<double>(i) / kTableSize;
    while (j + 2 < t_s.size() && t_s[j + 1] <= t) ++j;
    const double f = std::clamp((t - t_s[j]) / (t_s[j + 1] - t_s[j]), 0.0, 1.0);
    const double v = value[j] + f * (value[j + 1] - value[j]);
    w.table_[i] = static_cast<float>((v - lo) / range);
  }
  w.table_[kTableSize] = w.table_[0];  // close the cycle exactly
  return w;
}

double PulseWaveform::value(double phase) const noexcept {
  if (!std::isfinite(phase)) return 0.0;
  const double f = phase - std::floor(phase);  // 0 <= f < 1
  switch (shape_) {
    case WaveShape::rectangular: return f < param_ ? 1.0 : 0.0;
    case WaveShape::sawtooth: return f < param_ ? f / param_ : (1.0 - f) / (1.0 - param_);
    case WaveShape::table: {
      const double x = f * kTableSize;
      const std::size_t i = std::min(static_cast<std::size_t>(x), kTableSize - 1);
      const double a = x - static_cast<double>(i);
      return table_[i] + a * (table_[i + 1] - table_[i]);
    }
  }
  return 0.0;
}

double PulseWaveform::value_advanced(double phase, double rise_advance, double fall_advance) const noexcept {
  if (shape_ != WaveShape::rectangular) return value(phase);
  if (!std::isfinite(phase) || !std::isfinite(rise_advance) || !std::isfinite(fall_advance)) return value(phase);
  // Keep both advances inside one beat so the pulse neither vanishes nor fills the beat.
  const double rise = std::clamp(rise_advance, 0.0, 0.45), fall = std::clamp(fall_advance, 0.0, 0.45);
  const double x = phase + rise;
  const double f = x - std::floor(x);  // 0 at the advanced rising edge
  const double width = std::clamp(param_ + rise - fall, 0.01, 0.99);
  return f < width ? 1.0 : 0.0;
}

}  // namespace palprig
