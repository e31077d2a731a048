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
