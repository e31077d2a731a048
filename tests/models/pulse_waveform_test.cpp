// Pulse waveforms (rectangular, saw-tooth, lookup table) and the timestamp pulse clock: exact
// timing over long runs, rate changes with the phase kept, tables refused when empty or not
// periodic.
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "models/pulse_waveform.hpp"

using namespace palprig;

TEST(PulseWaveform, RectangularDutyCycle) {
  const PulseWaveform w = PulseWaveform::rectangular(0.2);
  EXPECT_EQ(w.value(0.0), 1.0);
  EXPECT_EQ(w.value(0.1999), 1.0);
  EXPECT_EQ(w.value(0.2001), 0.0);
  EXPECT_EQ(w.value(0.99), 0.0);
  EXPECT_EQ(w.value(7.1), 1.0);   // only the fraction of the phase counts
  EXPECT_EQ(w.value(-0.9), 1.0);  // -0.9 is 0.1 into a beat
  int on = 0;
  for (int i = 0; i < 10000; ++i) on += w.value(i / 10000.0) > 0.5;
  EXPECT_EQ(on, 2000);
  EXPECT_EQ(PulseWaveform().duty(), 0.2);  // default: paper 000's D = 0.2
}

TEST(PulseWaveform, SawtoothRisesFastAndFallsSlowly) {
  const PulseWaveform w = PulseWaveform::sawtooth(0.15);
  EXPECT_DOUBLE_EQ(w.value(0.0), 0.0);
  EXPECT_NEAR(w.value(0.075), 0.5, 1e-12);
  EXPECT_NEAR(w.value(0.15), 1.0, 1e-12);
  EXPECT_NEAR(w.value(0.575), 0.5, 1e-12);
  EXPECT_NEAR(w.value(0.9999), 0.0, 1e-3);
}

TEST(PulseWaveform, AdvancedEdgesStartAndEndTheRectangleEarly) {
  const PulseWaveform w = PulseWaveform::rectangular(0.2);
  // Rise 0.05 of a beat early, fall 0.02 early: on from -0.05 to 0.18.
  EXPECT_EQ(w.value_advanced(-0.04, 0.05, 0.02), 1.0);
  EXPECT_EQ(w.value_advanced(-0.06, 0.05, 0.02), 0.0);
  EXPECT_EQ(w.value_advanced(0.17, 0.05, 0.02), 1.0);
  EXPECT_EQ(w.value_advanced(0.19, 0.05, 0.02), 0.0);
  EXPECT_EQ(w.value_advanced(0.1, 0, 0), w.value(0.1));
  const PulseWaveform s = PulseWaveform::sawtooth();
  EXPECT_EQ(s.value_advanced(0.3, 0.1, 0.1), s.value(0.3));  // smooth shapes are tracked, not advanced
}

TEST(PulseWaveform, TableIsResampledAndNormalised) {
  // A triangle in mmHg: 80 -> 120 at a quarter of the beat -> 80.
  const PulseWaveform w = PulseWaveform::table({0.0, 0.2, 0.4, 0.6, 0.8}, {80, 120, 100, 90, 80});
  EXPECT_EQ(w.shape(), WaveShape::table);
  EXPECT_NEAR(w.recorded_period_s(), 0.8, 1e-12);
  EXPECT_NEAR(w.value(0.0), 0.0, 1e-6);
  EXPECT_NEAR(w.value(0.25), 1.0, 1e-6);
  EXPECT_NEAR(w.value(0.5), 0.5, 1e-6);
  EXPECT_NEAR(w.value(0.125), 0.5, 1e-6);
  EXPECT_NEAR(w.value(0.75), 0.25, 1e-6);
  EXPECT_NEAR(w.value(1.0), w.value(0.0), 1e-6);
}

TEST(PulseWaveform, BadTablesAndParametersAreRefused) {
  EXPECT_THROW(PulseWaveform::table({}, {}), palprig::BadInput);
  EXPECT_THROW(PulseWaveform::table({0, 1, 2}, {1, 2, 1}), palprig::BadInput);               // too short
  EXPECT_THROW(PulseWaveform::table({0, 1, 1, 2}, {1, 2, 3, 1}), palprig::BadInput);         // time not increasing
  EXPECT_THROW(PulseWaveform::table({0, 1, 2, 3}, {5, 5, 5, 5}), palprig::BadInput);         // flat
  EXPECT_THROW(PulseWaveform::table({0, 1, 2, 3}, {80, 120, 110, 100}), palprig::BadInput);  // does not close
  try {
    PulseWaveform::table({0, 1, 2, 3}, {80, 120, 110, 100});
  } catch (const palprig::BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("not periodic"), std::string::npos);
  }
  EXPECT_NO_THROW(PulseWaveform::table({0, 1, 2, 3}, {80, 120, 110, 81}));  // within 5 % of the range
  EXPECT_THROW(PulseWaveform::rectangular(0), palprig::BadInput);
  EXPECT_THROW(PulseWaveform::rectangular(1), palprig::BadInput);
  EXPECT_THROW(PulseWaveform::sawtooth(1.5), palprig::BadInput);
}

TEST(PulseClock, RateIsExactOverALongRunWhateverTheLoopTiming) {
  // One hour at 72 BPM, ticks about 1 ms apart with +/- 0.4 ms of jitter: the number of beats and
  // the time of each onset follow the timestamps, not the tick count.
  PulseClock clock{72.0, 0.0, 0.0};
  const PulseWaveform w = PulseWaveform::rectangular(0.2);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.0004, 0.0004);
  double t = 0, previous = w.value(clock.phase(0));
  long onsets = 0;
  double worst_error_s = 0;
  for (long k = 1; t < 3600.0; ++k) {
    t = k * 0.001 + jitter(rng);
    const double v = w.value(clock.phase(t));
    if (v > previous) {
      ++onsets;
      const double ideal = onsets * 60.0 / 72.0;
      worst_error_s = std::max(worst_error_s, std::abs(t - ideal));
    }
    previous = v;
  }
  EXPECT_EQ(onsets, 4320);           // 3600 s * 72 / 60, the first beat at t = 0 not counted
  EXPECT_LT(worst_error_s, 0.0019);  // each onset seen at the first tick after it (1 ms + jitter)
}

TEST(PulseClock, RateChangeKeepsThePhaseContinuous) {
  PulseClock c{60.0, 0.0, 0.0};
  EXPECT_NEAR(c.phase(10.25), 10.25, 1e-12);
  c.change_rate(120.0, 10.25);
  EXPECT_NEAR(c.phase(10.25), 10.25, 1e-12);  // no jump where the rate changes
  EXPECT_NEAR(c.phase(11.25), 12.25, 1e-12);  // then two beats per second
  c.change_rate(30.0, 11.25);
  EXPECT_NEAR(c.phase(13.25), 13.25, 1e-12);
}
