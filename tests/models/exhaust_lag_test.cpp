// The compensator's model of an exhaust that slows near 0 kPa against the simulated plant's: the
// lag at a pressure is the plant's, and the closed-form time of a free exhaust
// (RegulatorLag::exhaust_time_s) is the time the plant takes to empty from one level to another;
// and the tick's scene prefetch is asked only of maps too large for the cache.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "models/lag_compensator.hpp"
#include "models/pneumatic_plant.hpp"
#include "models/scene.hpp"

using namespace palprig;

TEST(ExhaustLag, TheCompensatorsModelIsThePlantsLagAtEachPressure) {
  PlantParams p;
  p.exhaust_time_constant_s = 0.070;
  p.exhaust_lag_factor_at_0 = 2.5;
  p.exhaust_lag_scale_kPa = 5;
  const RegulatorLag lag{0.005, 0.050, 2000, 0.070, 2.5, 5};
  for (double kPa : {0.0, 0.3, 1.0, 5.0, 20.0, 60.0})
    EXPECT_NEAR(lag.exhaust_tau_at(kPa), p.exhaust_time_constant_at(kPa), 1e-15) << kPa;
  EXPECT_NEAR(lag.exhaust_tau_at(0), 2.5 * 0.070, 1e-15);
  EXPECT_NEAR(lag.exhaust_tau_at(-1), 2.5 * 0.070, 1e-15);  // below 0: as at 0
  const RegulatorLag flat{0.005, 0.050, 2000, 0.070};
  EXPECT_EQ(flat.exhaust_tau_at(0.5), 0.070);
  EXPECT_FALSE(flat.exhaust_depends_on_pressure());
}

TEST(ExhaustLag, AFreeExhaustTakesTheClosedFormsTime) {
  // The plant vented from 12 kPa (no play, no dead time, no slew limit binding, fine steps): the
  // time it takes to reach each level against the integral of tau(p) dp / p.
  PlantParams p;
  p.hysteresis_kPa = 0;
  p.noise_sd_kPa = 0;
  p.dead_time_s = 0;
  p.slew_kPa_per_s = 1e9;
  p.exhaust_time_constant_s = 0.070;
  p.exhaust_lag_factor_at_0 = 2.5;
  p.exhaust_lag_scale_kPa = 5;
  const RegulatorLag lag{0, 0.050, 1e9, 0.070, 2.5, 5};
  PneumaticPlant plant(p);
  plant.reset(12.0);
  const double dt = 1e-6;
  double t = 0;
  for (double level : {8.0, 4.0, 1.0, 0.5}) {
    while (plant.output_kPa() > level) {
      plant.step(0.0, dt);
      t += dt;
    }
    const double closed = lag.exhaust_time_s(12.0, level);
    EXPECT_NEAR(t, closed, 2e-4 * closed + 2 * dt) << level;
  }
  // One lag at every pressure: tau ln(from / to).
  const RegulatorLag flat{0, 0.050, 1e9, 0.070};
  EXPECT_NEAR(flat.exhaust_time_s(12.0, 3.0), 0.070 * std::log(4.0), 1e-15);
  EXPECT_EQ(lag.exhaust_time_s(3.0, 12.0), 0.0);  // not a fall
  EXPECT_EQ(lag.exhaust_time_s(3.0, 0.0), 0.0);   // never reaches 0
}

TEST(ScenePrefetch, OnlyMapsLargerThanTheCacheAskForIt) {
  // The tick asks a scene for its samples ahead only where that pays: a map over 4 MiB. A hint
  // anywhere (inside, on the edges, outside, non-finite) reads nothing and changes nothing.
  const MapScene small(StiffnessMap(161, 121, 160.0, 120.0, std::vector<float>(std::size_t{161} * 121, 0.5f)),
                       MapSampling::nearest);
  const MapScene large(StiffnessMap(2048, 1024, 400.0, 200.0, std::vector<float>(std::size_t{2048} * 1024, 0.25f)),
                       MapSampling::bilinear);
  EXPECT_FALSE(small.prefetch_pays());
  EXPECT_TRUE(large.prefetch_pays());
  for (const Point2_mm p : {Point2_mm{0, 0}, Point2_mm{400, 200}, Point2_mm{-5, 300}, Point2_mm{NAN, 1}}) {
    large.prefetch(p);
    small.prefetch(p);
  }
  EXPECT_EQ(large.sample({400, 200}, 2.0, 0).stiffness, 0.25);
}
