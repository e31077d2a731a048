// The README's calibration recipe, verbatim, on the default simulated rig: paper 002's staircase
// (the sweep's default excitation) records 66 holds, fewer than 8 play operators need (68), so
// `calibrate fit` with its defaults fits the most operators the data supports and says so,
// instead of refusing; evaluate and run then work with the file.
#include <gtest/gtest.h>

#include "tests/support/run_process.hpp"

using namespace palprig::test_support;

TEST(CalibrationRecipe, DefaultStaircaseThenDefaultFitEvaluateAndRun) {
  TempDir dir;
  const std::string rig = source_dir() + "/data/rigs/simulated.json";
  const std::string data = (dir.path() / "DATA.csv").string(), cal = (dir.path() / "CAL.json").string();
  auto r = run_process(palprig_bin() + " calibrate sweep --rig " + rig +
                       " --channels 1,2,3 --from-kPa 10 --to-kPa 100 --step-kPa 10 --repeats 5 --out " + data);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_process(palprig_bin() + " calibrate fit " + data + " --out " + cal);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("channel 1: 7 play operators, the most its 66 quasi-static samples support"), std::string::npos)
      << r.out;
  // An explicit --operators 8 is still held to: refused with what to do.
  const auto strict = run_process(palprig_bin() + " calibrate fit " + data + " --operators 8 --out " +
                                  (dir.path() / "strict.json").string());
  EXPECT_EQ(strict.exit_code, 2) << strict.out << strict.err;
  EXPECT_NE(strict.err.find("68 quasi-static samples"), std::string::npos) << strict.err;
  r = run_process(palprig_bin() + " calibrate evaluate --rig " + rig + " --cal " + cal + " --min-improvement 5");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  r = run_process(palprig_bin() + " run --scene " + source_dir() + "/data/scenes/phantom_abc.json --rig " + rig +
                  " --cal " + cal);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}
