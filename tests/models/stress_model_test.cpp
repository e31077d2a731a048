#include <gtest/gtest.h>

#include <cmath>

#include "models/stress_model.hpp"

using namespace palprig;

// Paper 002 (REFERENCE.md): 11.75 kPa of air gives the 7.967 kPa hard-nodule fingertip stress.
TEST(ActuatorModel, PaperPairElevenSeventyFiveForSevenNineSixSeven) {
  const ActuatorModel a;
  EXPECT_NEAR(a.pressure_for_stress_kPa(7.967), 11.75, 1e-9);
  EXPECT_NEAR(a.stress_kPa(11.75), 7.967, 1e-9);
  EXPECT_NEAR(a.pressure_kPa(7.967, 1.0), 11.75, 1e-9);
}

TEST(ActuatorModel, InverseIsExactForAnyLine) {
  const ActuatorModel a{0.6, 1.2};
  for (double p : {0.0, 3.5, 11.75, 60.0, 100.0}) EXPECT_NEAR(a.pressure_for_stress_kPa(a.stress_kPa(p)), p, 1e-12);
}

TEST(ActuatorModel, NeverAsksForNegativePressureButPassesNaNToSafety) {
  const ActuatorModel a;
  EXPECT_EQ(a.pressure_kPa(0.0, 1.0), 0.0);
  EXPECT_TRUE(std::isnan(a.pressure_kPa(NAN, 1.0)));
}

TEST(StressModel, InterpolatesSoftToHardAtTheReferencePress) {
  const StressModel s;
  EXPECT_NEAR(s.target_stress_kPa(0.0, s.reference_force_N), 4.990, 1e-12);
  EXPECT_NEAR(s.target_stress_kPa(1.0, s.reference_force_N), 7.967, 1e-12);
  EXPECT_NEAR(s.target_stress_kPa(0.5, s.reference_force_N), (4.990 + 7.967) / 2, 1e-12);
  EXPECT_NEAR(s.target_stress_kPa(7.0, s.reference_force_N), 7.967, 1e-12);  // stiffness clamped
}

TEST(StressModel, ScalesWithForceAndSaturates) {
  const StressModel s;
  EXPECT_EQ(s.target_stress_kPa(1.0, 0.0), 0.0);
  EXPECT_NEAR(s.target_stress_kPa(1.0, s.reference_force_N / 2), 7.967 / 2, 1e-12);
  EXPECT_NEAR(s.target_stress_kPa(1.0, s.reference_force_N * 10), 7.967 * s.max_force_ratio, 1e-12);
  EXPECT_EQ(s.force_ratio(NAN), 0.0);
  EXPECT_EQ(s.force_ratio(-1.0), 0.0);
}

TEST(StressAndActuator, HardNodulePressureGrowsWithForceSoftTissueStaysAtZero) {
  const StressModel s;
  const ActuatorModel a;
  for (double f : {0.5, 1.0, 2.0, 4.0}) {
    const double r = s.force_ratio(f);
    EXPECT_NEAR(a.pressure_kPa(s.target_stress_kPa(0.0, f), r), 0.0, 1e-9) << f;
    EXPECT_NEAR(a.pressure_kPa(s.target_stress_kPa(1.0, f), r), 11.75 * r, 1e-9) << f;
  }
}
