// The regulator-lag compensator on the simulated plant (dead time + first-order lag + slew):
// it respects the rig's limits, tracks smooth waveforms without lag, and keeps a rectangular
// pulse's shape far better than feeding the wave straight to the regulator.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "models/pneumatic_plant.hpp"
#include "models/pulse_renderer.hpp"
#include "models/pulse_waveform.hpp"

using namespace palprig;

namespace {

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= double(a.size());
  mb /= double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

struct RenderResult {
  double correlation;
  double max_command_kPa;
  double max_step_kPa;
};

// A pulse of amplitude A riding on a base pressure, 1 kHz, rendered on a plant without play
// or noise (the lag alone: what this compensator is for). Mirrors the tick's pulse stage.
RenderResult render(const PulseWaveform& wave, double bpm, bool compensate, double base_kPa = 4.0,
                    double amplitude_kPa = 8.0) {
  PlantParams pp;
  pp.hysteresis_kPa = 0;
  pp.noise_sd_kPa = 0;
  PneumaticPlant plant(pp);
  plant.reset(base_kPa);
  const RegulatorLag lag{pp.dead_time_s, pp.time_constant_s, pp.slew_kPa_per_s};
  LagCompensator comp;
  const PulseClock clock{bpm, 0, 0};
  const double dt = 0.001, p_max = 60, slew = 2000;
  double previous = base_kPa;
  RenderResult r{0, 0, 0};
  std::vector<double> want, got;
  for (int k = 0; k < 12000; ++k) {
    const double t = k * dt;
    const double f = bpm / 60;
    const double now = amplitude_kPa * wave.value(clock.phase(t));
    const double ahead =
        amplitude_kPa * wave.value_advanced(clock.phase(t + lag.dead_time_s + dt), comp.rise_anticipation_s() * f,
                                            comp.fall_anticipation_s() * f);
    double u = now;
    if (compensate) u = comp.command(lag, ahead, -base_kPa, p_max - base_kPa, slew * dt, k > 0 ? dt : 0);
    const double command = base_kPa + u;
    if (k > 0) {
      r.max_step_kPa = std::max(r.max_step_kPa, std::abs(command - previous));
      plant.step(previous, dt);
    }
    previous = command;
    r.max_command_kPa = std::max(r.max_command_kPa, command);
    EXPECT_GE(command, 0.0);
    if (k >= 2000) {
      want.push_back(now);
      got.push_back(plant.output_kPa());
    }
  }
  r.correlation = pearson(want, got);
  return r;
}

}  // namespace

TEST(PulseCompensation, KeepsARectangularPulsesShapeOnTheLaggingRegulator) {
  const PulseWaveform rect = PulseWaveform::rectangular(0.2);
  for (double bpm : {60.0, 100.0}) {
    const RenderResult raw = render(rect, bpm, false), comp = render(rect, bpm, true);
    EXPECT_GE(comp.correlation, 0.95) << bpm;
    EXPECT_GT(comp.correlation, raw.correlation + 0.15) << bpm;
    EXPECT_LE(comp.max_command_kPa, 60.0 + 1e-9);
    EXPECT_LE(comp.max_step_kPa, 2.0 + 1e-9);  // the command's slew limit (2000 kPa/s at 1 kHz)
  }
  EXPECT_GT(render(rect, 160, true).correlation, render(rect, 160, false).correlation + 0.3);
}

TEST(PulseCompensation, TracksASmoothWaveformWithoutLag) {
  const PulseWaveform saw = PulseWaveform::sawtooth(0.15);
  const RenderResult raw = render(saw, 100, false), comp = render(saw, 100, true);
  EXPECT_GT(comp.correlation, 0.99);
  EXPECT_LT(raw.correlation, 0.9);  // uncompensated it lags by the dead time plus tau
}

TEST(PulseCompensation, StaysWithinTheBoundsItIsGiven) {
  LagCompensator c;
  const RegulatorLag lag;
  double last = 0;
  for (int k = 0; k < 2000; ++k) {
    const double want = (k / 100) % 2 ? 30.0 : -5.0;  // asks for more than allowed both ways
    const double u = c.command(lag, want, -2.0, 10.0, 1.5, 0.001);
    EXPECT_GE(u, -2.0);
    EXPECT_LE(u, 10.0);
    EXPECT_LE(std::abs(u - last), 1.5 + 1e-12);
    last = u;
  }
  LagCompensator first;
  EXPECT_EQ(first.command(lag, 3.0, -1, 5, 1, 0.0), 3.0);  // no time step: passed through
  EXPECT_EQ(first.predicted_kPa(), 0.0);
  EXPECT_TRUE(std::isnan(first.command(lag, std::nan(""), -1, 5, 1, 0.001)));  // left for the safety stage
}

TEST(PulseCompensation, LearnsHowEarlyEdgesMustStart) {
  LagCompensator c;
  const RegulatorLag lag;
  for (int k = 0; k < 3000; ++k) c.command(lag, (k / 300) % 2 ? 8.0 : 0.0, -4.0, 56.0, 2.0, 0.001);
  // Half-way takes several milliseconds with a 50 ms regulator and a 2 kPa/ms command slew.
  EXPECT_GT(c.rise_anticipation_s(), 0.003);
  EXPECT_LT(c.rise_anticipation_s(), 0.05);
  EXPECT_GT(c.fall_anticipation_s(), 0.003);
  EXPECT_LT(c.fall_anticipation_s(), 0.05);
}
