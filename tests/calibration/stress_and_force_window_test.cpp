// The actuator stress line (paper 002 fig. 12) and the pulse force window (paper 003), from
// the files a lab engineer writes, with the paper's figures as oracles.
#include <gtest/gtest.h>

#include "calibration/force_window.hpp"
#include "calibration/stress_fit.hpp"
#include "core/input_error.hpp"
#include <functional>

#include "tests/support/refusal.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::refusal;
using palprig::test_support::TempDir;

TEST(StressLine, PaperLineGivesElevenPointSevenFiveKiloPascalForTheNodule) {
  // Pairs on paper 002's line: 4.990 kPa uninflated, 7.967 kPa at 11.75 kPa of air.
  TempDir dir;
  std::string text = "pressure_kPa,stress_kPa\n";
  const double slope = (7.967 - 4.990) / 11.75;
  for (int p = 0; p <= 100; p += 10) text += std::to_string(p) + "," + std::to_string(4.990 + slope * p) + "\n";
  const auto file = dir.write("fe.csv", text);
  const auto pairs = read_stress_pairs_csv(file);
  ASSERT_EQ(pairs.size(), 11u);
  const ActuatorFit fit = fit_actuator_stress(pairs, 2, file.string());
  EXPECT_NEAR(fit.model.slope, slope, 1e-6);
  EXPECT_NEAR(fit.model.intercept_kPa, 4.990, 1e-5);
  EXPECT_GT(fit.line.r_squared, 0.999999);
  EXPECT_NEAR(fit.model.pressure_for_stress_kPa(7.967), 11.75, 1e-3);  // the inverse
}

TEST(StressLine, PerChannelRowsAndSharedRows) {
  TempDir dir;
  const auto file = dir.write("pairs.csv",
                              "pressure_kPa,stress_kPa,channel\n"
                              "0,5,\n10,7,\n20,9,\n"  // shared: slope 0.2
                              "0,5,3\n10,8,3\n20,11,3\n");
  const auto pairs = read_stress_pairs_csv(file);
  EXPECT_NEAR(fit_actuator_stress(pairs, 1, "f").model.slope, 0.2, 1e-12);
  // Channel 3 also has its own steeper pairs: the fit pools both.
  EXPECT_GT(fit_actuator_stress(pairs, 3, "f").model.slope, 0.2);
}

TEST(StressLine, RefusesBadPairs) {
  TempDir dir;
  auto fit = [&](const std::string& text) {
    const auto f = dir.write("p.csv", text);
    return refusal([&] { fit_actuator_stress(read_stress_pairs_csv(f), 1, f.string()); });
  };
  const std::string f = (dir.path() / "p.csv").string();
  EXPECT_EQ(fit("pressure,stress\n1,2\n"),
            f + ": line 1: columns pressure_kPa, stress_kPa and optionally channel, got \"pressure\"");
  EXPECT_EQ(fit("pressure_kPa,stress_kPa\n1,2\n2,nan\n"),
            f + ": line 3: a finite number in column stress_kPa, got \"nan\"");
  EXPECT_EQ(fit("pressure_kPa,stress_kPa,channel\n1,2,4\n"), f + ": line 2: a channel 1..3 (or empty for all)");
  EXPECT_EQ(fit("pressure_kPa,stress_kPa\n0,5\n10,5\n20,5\n"),
            f + ": stress line of channel 1: a response that moves (all 3 readings are 5)");
  EXPECT_EQ(fit("pressure_kPa,stress_kPa\n0,9\n10,7\n20,5\n"),
            f + ": stress line of channel 1: a fingertip stress that rises with air pressure (the fitted slope is -0.2 "
                "kPa/kPa)");
  EXPECT_EQ(fit("pressure_kPa,stress_kPa\n0,9\n10,7\n"),
            f + ": stress line of channel 1: at least 3 points for a line, got 2");
}

TEST(ForceWindow, MeansOfTheReferencePresses) {
  TempDir dir;
  const auto file = dir.write("presses.csv",
                              "# cuff over the sensor, brachial artery\nreference_mmHg,force_N\n"
                              "60,1.1\n60,1.3\n60,1.2\n120,2.5\n120,2.3\n");
  const ForceWindowFit w = force_window_from_presses(file);
  EXPECT_NEAR(w.window.f_min_N, 1.2, 1e-12);
  EXPECT_NEAR(w.window.f_max_N, 2.4, 1e-12);
  EXPECT_NEAR(w.f_min_sd_N, 0.1, 1e-12);
  EXPECT_NEAR(w.f_max_sd_N, std::sqrt(0.02), 1e-12);
  EXPECT_EQ(w.presses_min, 3u);
  EXPECT_EQ(w.presses_max, 2u);
  EXPECT_EQ(w.window.diastolic_mmHg, 60);
  EXPECT_EQ(w.window.systolic_mmHg, 120);
}

TEST(ForceWindow, RefusesBadPresses) {
  TempDir dir;
  auto window = [&](const std::string& text) {
    const auto f = dir.write("w.csv", text);
    return refusal([&] { force_window_from_presses(f); });
  };
  const std::string f = (dir.path() / "w.csv").string();
  EXPECT_EQ(window("reference_mmHg,force_N\n60,1\n90,2\n"),
            f + ": line 3: a reference press at 60 (diastolic) or 120 mmHg (systolic), got 90");
  EXPECT_EQ(window("reference_mmHg,force_N\n60,1\n"), f + ": presses: at least one press at the systolic reference");
  EXPECT_EQ(window("reference_mmHg,force_N\n60,2\n120,1.5\n"),
            f + ": presses: a systolic press force above the diastolic one (got F_min 2 N, F_max 1.5 N)");
  EXPECT_EQ(window("reference_mmHg,force_N\n60,-1\n"), f + ": line 2: a pressing force >= 0 N");
  EXPECT_EQ(window("mmHg,N\n"), f + ": line 1: the header reference_mmHg,force_N");
}
