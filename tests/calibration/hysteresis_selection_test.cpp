// The hysteresis model class is chosen by held-out error over the sweep's runs: the symmetric
// model on a symmetric plant, the asymmetric one on an asymmetric plant, each measured on runs
// its fit did not see.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "calibration/hysteresis_selection.hpp"
#include "models/pneumatic_plant.hpp"

using namespace palprig;

namespace {

struct Runs {
  std::vector<double> x, y;
  std::vector<std::size_t> starts;
};

// Quasi-static holds of a simulated regulator (settled: no lag), in runs each from a vent: five
// staircases 10..60..10 kPa, a run of random levels and a shrinking sine, the sweep's layout
// (calibration/sweep_plan.hpp).
Runs sweep_of(const PlantParams& params) {
  PneumaticPlant plant(params);
  Runs r;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> level(10, 60);
  auto hold = [&](double command) {
    for (int k = 0; k < 500; ++k) plant.step(command, 0.001);  // settled
    double sum = 0;
    for (int k = 0; k < 30; ++k) sum += plant.monitor_kPa();
    r.x.push_back(command);
    r.y.push_back(sum / 30);
  };
  for (int run = 0; run < 7; ++run) {
    r.starts.push_back(r.x.size());
    hold(0.0);
    if (run < 5) {
      for (int l = 10; l <= 60; l += 10) hold(l);
      for (int l = 60; l >= 10; l -= 10) hold(l);
    } else if (run == 5) {
      for (int k = 0; k < 60; ++k) hold(level(rng));
    } else {
      for (int k = 0; k <= 60; ++k)  // 5 cycles of 12 holds, the amplitude shrinking to a quarter
        hold(35 - 25 * (1 - 0.75 * k / 60.0) * std::cos(2 * 3.141592653589793 * k / 12.0));
    }
  }
  return r;
}

}  // namespace

TEST(HysteresisSelection, SymmetricPlantKeepsTheSymmetricModel) {
  PlantParams p;  // the shipped simulated regulator: a 2 kPa play both ways
  const Runs r = sweep_of(p);
  const HysteresisSelection s = select_hysteresis_model(r.x, r.y, r.starts, HysteresisFitOptions{});
  ASSERT_TRUE(s.compared) << s.reason;
  EXPECT_EQ(s.folds, 7u);
  EXPECT_FALSE(s.asymmetric_chosen) << s.reason;
  EXPECT_NE(s.reason.find("symmetric ("), std::string::npos) << s.reason;
}

// Fitted as the regulator runs its plays, both classes fit a symmetric regulator's holds to a few
// hundredths of a kPa, where one may beat the other by 10 % by chance: the asymmetric model must
// also be 0.05 kPa better outright. The rule on the figures the recipe gave (docs/rig.md), then on
// a noise-free symmetric plant.
TEST(HysteresisSelection, ATenPercentGainOfHundredthsOfAKpaKeepsTheSymmetricModel) {
  EXPECT_FALSE(asymmetric_model_wins(0.026, 0.023, 0.10, 0.05));  // 12 % but 0.003 kPa: the default rig
  EXPECT_TRUE(asymmetric_model_wins(0.026, 0.023, 0.10, 0.0));    // what the 10 % alone chose
  EXPECT_TRUE(asymmetric_model_wins(0.293, 0.077, 0.10, 0.05));   // the asymmetric regulator
  EXPECT_FALSE(asymmetric_model_wins(0.300, 0.280, 0.10, 0.05));  // 0.02 kPa and 7 %
  EXPECT_FALSE(asymmetric_model_wins(0.600, 0.560, 0.10, 0.0));   // 0.04 kPa but 7 %
  EXPECT_TRUE(asymmetric_model_wins(0.600, 0.530, 0.10, 0.05));   // 12 % and 0.07 kPa

  PlantParams p;
  p.noise_sd_kPa = 0.0;
  const Runs r = sweep_of(p);
  const HysteresisSelection s = select_hysteresis_model(r.x, r.y, r.starts, HysteresisFitOptions{});
  ASSERT_TRUE(s.compared) << s.reason;
  EXPECT_LT(s.symmetric.rms_kPa, 0.05) << s.reason;
  EXPECT_FALSE(s.asymmetric_chosen) << s.reason;
  EXPECT_EQ(s.min_gain_kPa, 0.05);
}

TEST(HysteresisSelection, AsymmetricPlantGetsTheAsymmetricModel) {
  PlantParams p;
  p.hysteresis_rising_kPa = 3.0;  // lags three times more rising than falling
  p.hysteresis_falling_kPa = 1.0;
  const Runs r = sweep_of(p);
  const HysteresisSelection s = select_hysteresis_model(r.x, r.y, r.starts, HysteresisFitOptions{});
  ASSERT_TRUE(s.compared) << s.reason;
  EXPECT_TRUE(s.asymmetric_chosen) << s.reason;
  EXPECT_LT(s.asymmetric.rms_kPa, 0.5 * s.symmetric.rms_kPa) << s.reason;
  EXPECT_NE(s.reason.find("asymmetric ("), std::string::npos) << s.reason;
  EXPECT_NE(s.reason.find("x lower"), std::string::npos) << s.reason;
}

TEST(HysteresisSelection, OneRunIsNotACompetition) {
  PlantParams p;
  p.hysteresis_rising_kPa = 3.0;
  p.hysteresis_falling_kPa = 1.0;
  const Runs r = sweep_of(p);
  const std::vector<std::size_t> one_run{0};
  const HysteresisSelection s = select_hysteresis_model(r.x, r.y, one_run, HysteresisFitOptions{});
  EXPECT_FALSE(s.compared);
  EXPECT_FALSE(s.asymmetric_chosen);
  EXPECT_NE(s.reason.find("nothing to hold out"), std::string::npos) << s.reason;
}
