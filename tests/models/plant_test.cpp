#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "models/pneumatic_plant.hpp"

using namespace palprig;

namespace {
PlantParams ideal_lag(double tau_s, double dead_s) {
  PlantParams p;
  p.time_constant_s = tau_s;
  p.dead_time_s = dead_s;
  p.hysteresis_kPa = 0;
  p.noise_sd_kPa = 0;
  p.slew_kPa_per_s = 1e6;
  return p;
}
}  // namespace

TEST(PneumaticPlant, StepResponseHasTheConfiguredTimeConstant) {
  PneumaticPlant plant(ideal_lag(0.05, 0.0));
  const double dt = 1e-4;
  double t = 0, t63 = -1;
  while (t < 0.5) {
    const double y = plant.step(50.0, dt);
    t += dt;
    if (t63 < 0 && y >= 50.0 * (1 - std::exp(-1.0))) t63 = t;
  }
  EXPECT_NEAR(t63, 0.05, 0.002);
  EXPECT_NEAR(plant.output_kPa(), 50.0, 50.0 * std::exp(-9.0));  // 10 time constants
}

TEST(PneumaticPlant, DeadTimeDelaysTheResponse) {
  PneumaticPlant plant(ideal_lag(0.0, 0.010));
  const double dt = 0.001;
  for (int k = 1; k <= 9; ++k) EXPECT_EQ(plant.step(40.0, dt), 0.0) << k << " ms";
  EXPECT_NEAR(plant.step(40.0, dt), 40.0, 1e-9);  // 10 ms later, with no lag
}

TEST(PneumaticPlant, SlewLimitBoundsTheRate) {
  PlantParams p = ideal_lag(0.0, 0.0);
  p.slew_kPa_per_s = 100.0;
  PneumaticPlant plant(p);
  EXPECT_NEAR(plant.step(80.0, 0.1), 10.0, 1e-9);
  EXPECT_NEAR(plant.step(80.0, 0.1), 20.0, 1e-9);
}

TEST(PneumaticPlant, StaysInRangeWhateverTheCommand) {
  PneumaticPlant plant(ideal_lag(0.0, 0.0));
  EXPECT_EQ(plant.step(500.0, 0.01), 100.0);
  EXPECT_EQ(plant.step(-20.0, 0.01), 0.0);
  EXPECT_EQ(plant.step(NAN, 0.01), 0.0);  // non-finite command vents
}

TEST(PneumaticPlant, HysteresisSeparatesInflationAndDeflation) {
  PlantParams p = ideal_lag(0.0, 0.0);
  p.hysteresis_kPa = 3.0;
  PneumaticPlant plant(p);
  const double up = plant.step(50.0, 0.01);  // rising: output lags the command by r
  EXPECT_NEAR(up, 47.0, 1e-9);
  plant.step(80.0, 0.01);
  const double down = plant.step(50.0, 0.01);  // falling: output stays above by r
  EXPECT_NEAR(down, 53.0, 1e-9);
}

TEST(PneumaticPlant, NoiseIsSeededAndOnlyOnTheMonitor) {
  PlantParams p = ideal_lag(0.0, 0.0);
  p.noise_sd_kPa = 0.5;
  PneumaticPlant a(p), b(p);
  a.step(30.0, 0.01);
  b.step(30.0, 0.01);
  EXPECT_EQ(a.output_kPa(), 30.0);
  double sum_sq = 0;
  for (int i = 0; i < 2000; ++i) {
    const double ma = a.monitor_kPa();
    EXPECT_EQ(ma, b.monitor_kPa());
    sum_sq += (ma - 30.0) * (ma - 30.0);
  }
  EXPECT_NEAR(std::sqrt(sum_sq / 2000), 0.5, 0.05);
}

TEST(PneumaticPlant, RefusesImpossibleParameters) {
  PlantParams p;
  p.time_constant_s = -1;
  EXPECT_THROW(PneumaticPlant{p}, palprig::BadInput);
  p = {};
  p.min_kPa = 50;
  p.max_kPa = 10;
  EXPECT_THROW(PneumaticPlant{p}, palprig::BadInput);
}

// The default plant (2 kPa play) once read about 2 kPa after a vent, so a 0 kPa stimulus
// was felt at 2 kPa. A regulator commanded to 0 exhausts to 0; above 2 r the play is unchanged.
TEST(PneumaticPlant, ACommandOfZeroExhaustsToZero) {
  PlantParams p = ideal_lag(0.0, 0.0);
  p.hysteresis_kPa = 2.0;
  PneumaticPlant plant(p);
  plant.step(30.0, 0.01);
  EXPECT_NEAR(plant.step(0.0, 0.01), 0.0, 1e-12);
  // With the default rig's lag and dead time too: 0.5 s after a vent from 30 kPa.
  PneumaticPlant lagged(PlantParams{});
  for (int k = 0; k < 500; ++k) lagged.step(30.0, 0.001);
  for (int k = 0; k < 500; ++k) lagged.step(0.0, 0.001);
  EXPECT_LT(lagged.output_kPa(), 0.01);
  // Deflating to a small command keeps at most the command's distance to the bottom of play.
  plant.step(30.0, 0.01);
  EXPECT_NEAR(plant.step(1.0, 0.01), 2.0, 1e-12);
  plant.step(30.0, 0.01);
  EXPECT_NEAR(plant.step(4.0, 0.01), 6.0, 1e-12);  // full +r above 2 r
}

// A regulator that is not symmetric: each behaviour against its closed form.

TEST(PneumaticPlant, AsymmetricPlayLagsRisingAndFallingByTheirOwnWidths) {
  PlantParams p = ideal_lag(0.0, 0.0);
  p.hysteresis_rising_kPa = 3.0;
  p.hysteresis_falling_kPa = 1.0;
  PneumaticPlant plant(p);
  EXPECT_NEAR(plant.step(50.0, 0.01), 47.0, 1e-12);  // rising: x - r_rise
  plant.step(80.0, 0.01);                            // 77
  EXPECT_NEAR(plant.step(76.5, 0.01), 77.0, 1e-12);  // inside the band: held
  EXPECT_NEAR(plant.step(50.0, 0.01), 51.0, 1e-12);  // falling: x + r_fall
  EXPECT_NEAR(plant.step(52.0, 0.01), 51.0, 1e-12);  // reversal: flat across the band of 4 kPa
  EXPECT_NEAR(plant.step(56.0, 0.01), 53.0, 1e-12);  // then x - r_rise again
  // A 0 kPa command still exhausts to 0: the band above narrows to the distance from the bottom.
  EXPECT_NEAR(plant.step(0.5, 0.01), 1.0, 1e-12);
  EXPECT_NEAR(plant.step(0.0, 0.01), 0.0, 1e-12);
}

TEST(PneumaticPlant, UnsetAsymmetryIsTheSymmetricPlantExactly) {
  // Defaults reproduce the symmetric regulator bit for bit (stored study figures depend on it).
  PlantParams symmetric;
  PlantParams spelled = symmetric;
  spelled.hysteresis_rising_kPa = symmetric.hysteresis_kPa;
  spelled.hysteresis_falling_kPa = symmetric.hysteresis_kPa;
  spelled.exhaust_time_constant_s = symmetric.time_constant_s;
  PneumaticPlant a(symmetric), b(spelled);
  for (int k = 0; k < 3000; ++k) {
    const double command = 30.0 + 25.0 * std::sin(k * 0.01) + (k % 700 < 50 ? -30.0 : 0.0);
    ASSERT_EQ(a.step(command, 0.001), b.step(command, 0.001)) << k;
    ASSERT_EQ(a.monitor_kPa(), b.monitor_kPa()) << k;
  }
}

TEST(PneumaticPlant, FillsAndExhaustsWithTheirOwnTimeConstants) {
  PlantParams p = ideal_lag(0.04, 0.0);
  p.exhaust_time_constant_s = 0.12;
  PneumaticPlant plant(p);
  const double dt = 1e-4;
  // Filling from 0 toward 50: y = 50 (1 - exp(-t / 0.04)); exactly, the discretisation is exact.
  for (int k = 1; k <= 1000; ++k) {
    const double y = plant.step(50.0, dt);
    if (k % 100 == 0) {
      ASSERT_NEAR(y, 50.0 * (1 - std::exp(-k * dt / 0.04)), 1e-9) << k;
    }
  }
  const double top = plant.output_kPa();
  // Exhausting toward 10: y = 10 + (top - 10) exp(-t / 0.12).
  for (int k = 1; k <= 3000; ++k) {
    const double y = plant.step(10.0, dt);
    if (k % 100 == 0) {
      ASSERT_NEAR(y, 10.0 + (top - 10.0) * std::exp(-k * dt / 0.12), 1e-9) << k;
    }
  }
}

TEST(PneumaticPlant, ExhaustSlowsNearZeroAsItsClosedForm) {
  // tau(y) = tau_e (1 + (F - 1) s / (y + s)) toward 0 kPa: dy/dt = -y (y + s) / (tau_e (y + F s)),
  // whose solution satisfies F ln(y / y0) + (1 - F) ln((y + s) / (y0 + s)) = -t / tau_e.
  const double tau = 0.05, F = 3.0, s = 8.0, y0 = 40.0;
  PlantParams p = ideal_lag(tau, 0.0);
  p.exhaust_lag_factor_at_0 = F;
  p.exhaust_lag_scale_kPa = s;
  EXPECT_DOUBLE_EQ(p.exhaust_time_constant_at(0.0), F * tau);
  EXPECT_NEAR(p.exhaust_time_constant_at(1e6), tau, 1e-6);
  PneumaticPlant plant(p);
  plant.reset(y0);
  const double dt = 1e-5;
  for (int k = 1; k <= 40000; ++k) {
    const double y = plant.step(0.0, dt);
    if (k % 2000 == 0) {
      const double t_closed = -tau * (F * std::log(y / y0) + (1 - F) * std::log((y + s) / (y0 + s)));
      ASSERT_NEAR(k * dt, t_closed, 2e-3 * k * dt) << "y " << y;
    }
  }
  // Three times slower at the bottom than a plain lag would be: still above the plain lag's value.
  EXPECT_GT(plant.output_kPa(), y0 * std::exp(-0.4 / tau) * 10);
  // Filling is not affected.
  PneumaticPlant filling(p);
  EXPECT_NEAR(filling.step(20.0, 0.01), 20.0 * (1 - std::exp(-0.01 / tau)), 1e-12);
}

TEST(PneumaticPlant, SaturatingGainSettlesOnItsTanh) {
  PlantParams p = ideal_lag(0.02, 0.0);
  p.gain_saturation_kPa = 60.0;
  PneumaticPlant plant(p);
  for (double x : {10.0, 30.0, 55.0, 90.0}) {
    for (int k = 0; k < 1000; ++k) plant.step(x, 0.001);  // 50 time constants
    EXPECT_NEAR(plant.output_kPa(), 60.0 * std::tanh(x / 60.0), 1e-9) << x;
  }
  // With a play, the saturation acts on what the play passes: x - r rising.
  p.hysteresis_kPa = 2.0;
  PneumaticPlant with_play(p);
  for (int k = 0; k < 1000; ++k) with_play.step(40.0, 0.001);
  EXPECT_NEAR(with_play.output_kPa(), 60.0 * std::tanh(38.0 / 60.0), 1e-9);
}

TEST(PneumaticPlant, RefusesImpossibleAsymmetricParameters) {
  PlantParams p;
  p.hysteresis_rising_kPa = -1;
  EXPECT_THROW(PneumaticPlant{p}, palprig::BadInput);
  p = {};
  p.exhaust_lag_factor_at_0 = 0.5;
  EXPECT_THROW(PneumaticPlant{p}, palprig::BadInput);
  p = {};
  p.exhaust_time_constant_s = NAN;
  EXPECT_THROW(PneumaticPlant{p}, palprig::BadInput);
}
