// The live view's rendering error: RMS of monitor - target over the last seconds, against its
// closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "models/rolling_rms.hpp"

using namespace palprig;

TEST(RollingRms, ConstantAndSineErrorsGiveTheirClosedForms) {
  RollingRms r(5.0);
  EXPECT_TRUE(std::isnan(r.rms_kPa()));
  for (int k = 0; k < 300; ++k) r.push(k / 60.0, -0.4);
  EXPECT_NEAR(r.rms_kPa(), 0.4, 1e-12);
  // A sine of amplitude A over whole periods: A / sqrt(2).
  RollingRms s(5.0);
  for (int k = 0; k < 600; ++k) s.push(k / 60.0, 0.3 * std::sin(2 * M_PI * 2.0 * k / 60.0));
  EXPECT_NEAR(s.rms_kPa(), 0.3 / std::sqrt(2.0), 0.005);
}

TEST(RollingRms, OnlyTheLastWindowCounts) {
  RollingRms r(2.0);
  for (int k = 0; k <= 600; ++k) r.push(k / 60.0, k <= 300 ? 3.0 : 0.1);  // a drift that ended 5 s ago
  EXPECT_NEAR(r.rms_kPa(), 0.1, 1e-12);
  EXPECT_LE(r.samples(), std::size_t(2.0 * 60 + 1));
}

TEST(RollingRms, SkipsMissingReadingsAndStartsOverWithANewRun) {
  RollingRms r(5.0);
  r.push(0.0, 1.0);
  r.push(0.1, NAN);  // no monitor reading
  r.push(0.2, 1.0);
  EXPECT_EQ(r.samples(), 2u);
  EXPECT_NEAR(r.rms_kPa(), 1.0, 1e-12);
  r.push(0.05, 0.2);  // time went back: a new run
  EXPECT_EQ(r.samples(), 1u);
  EXPECT_NEAR(r.rms_kPa(), 0.2, 1e-12);
  // A full ring drops its oldest: never more than kCapacity samples.
  RollingRms fast(100.0);
  for (int k = 0; k < 2000; ++k) fast.push(k * 1e-3, k < 1000 ? 5.0 : 1.0);
  EXPECT_EQ(fast.samples(), RollingRms::kCapacity);
  EXPECT_NEAR(fast.rms_kPa(), 1.0, 1e-12);
}
