// The per-region table of `demo` and `run --regions` after a fault (an outage that outlasted
// max_outage_s): the monitor read nothing while the link was down, and the run ended before
// the fingers reached the tumors. It printed "soft tissue ... nan / 1.06" and "WARNING: a tumor
// did not get higher pressure than soft tissue" for tumors never pressed on; it now says the
// run faulted, averages only the readings there were, and marks the regions not reached.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "controller/region_table.hpp"

namespace palprig {
namespace {

TelemetryRecord pressing_soft_tissue(double t, float monitor) {
  TelemetryRecord r;
  r.t_s = t;
  r.flags = kInContact;
  for (int f = 0; f < kFingerCount; ++f) {
    r.finger_x_mm[f] = 10.0f + 16.0f * float(f);
    r.finger_y_mm[f] = 10.0f;
    r.finger_force_N[f] = 2.0f;
    r.target_kPa[f] = 0.6f;
    r.monitor_kPa[f] = monitor;
  }
  return r;
}

TEST(RegionTable, AfterAFaultItSaysSoAndPrintsNoNan) {
  RegionTable table({{"A", 80, 60, 4}, {"B", 120, 90, 10}}, 0.05);
  for (int i = 0; i < 100; ++i) table.on_tick(pressing_soft_tissue(0.001 * i, 0.9f + 0.001f * float(i)));
  for (int i = 100; i < 150; ++i) table.on_tick(pressing_soft_tissue(0.001 * i, std::nanf("")));  // link down
  std::ostringstream out;
  table.print(out, "link outage longer than max_outage_s", 2.15);
  const std::string text = out.str();
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  EXPECT_EQ(text.find("did not get higher"), std::string::npos) << text;
  EXPECT_NE(text.find("The run faulted at t = 2.15 s (link outage longer than max_outage_s)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("not reached: tumor A, tumor B"), std::string::npos) << text;
  EXPECT_NE(text.find("tumor A (r 4 mm)             0      not reached"), std::string::npos) << text;
  // Soft tissue: 450 finger-ticks, the plant averaged over the 300 with a reading.
  EXPECT_EQ(table.rows().back().n, 450u);
  EXPECT_EQ(table.rows().back().plant_n, 300u);
  EXPECT_NEAR(table.rows().back().plant_mean(), 0.9495, 1e-4);
  // JSON: null where nothing was measured (it has no NaN).
  const auto j = table.json();
  EXPECT_TRUE(j[0]["target_kPa_mean"].is_null());
  EXPECT_TRUE(j[2]["plant_kPa_mean"].is_number());
  EXPECT_FALSE(table.tumors_feel_harder());
}

TEST(RegionTable, ARunWithoutFaultNamesATumorItNeverReached) {
  RegionTable table({{"A", 80, 60, 4}}, 0.05);
  for (int i = 0; i < 10; ++i) table.on_tick(pressing_soft_tissue(0.001 * i, 0.5f));
  std::ostringstream out;
  table.print(out);
  EXPECT_NE(out.str().find("WARNING: not pressed on during the run: tumor A; no comparison for it."), std::string::npos)
      << out.str();
}

}  // namespace
}  // namespace palprig
