// A hand-typed sensor table (caliper readings) without a "# sensor:" line: the sensor is named
// after its column, so the fit's report, chart titles and axes never show an empty name
// ("Channel 1:  against command" with no y label).
#include <gtest/gtest.h>

#include "calibration/sweep_csv.hpp"
#include "tests/support/temp_dir.hpp"

namespace palprig {
namespace {

TEST(SweepSensorName, UnnamedSensorColumnIsCalledSensor) {
  test_support::TempDir dir;
  const auto file =
      dir.write("caliper.csv",
                "# rig_id: bench\n"
                "channel,branch,repeat,command_kPa,sensor\n"
                "1,inflation,1,10,0.8\n1,inflation,1,20,1.7\n1,deflation,1,20,1.9\n1,deflation,1,10,1.0\n");
  const SweepData data = read_sweep_csv(file);
  EXPECT_TRUE(data.has_sensor);
  EXPECT_EQ(data.info.sensor_name, "sensor");
}

TEST(SweepSensorName, NamedSensorKeepsItsName) {
  test_support::TempDir dir;
  const auto file = dir.write("caliper.csv",
                              "# rig_id: bench\n# sensor: deformation_mm\n"
                              "channel,branch,repeat,command_kPa,sensor\n1,inflation,1,10,0.8\n1,deflation,1,10,1.0\n");
  EXPECT_EQ(read_sweep_csv(file).info.sensor_name, "deformation_mm");
}

TEST(SweepSensorName, NoSensorColumnNoName) {
  test_support::TempDir dir;
  const auto file = dir.write("monitor.csv", "# rig_id: bench\nchannel,command_kPa,monitor_kPa\n1,10,9.8\n1,20,19.7\n");
  EXPECT_EQ(read_sweep_csv(file).info.sensor_name, "");
}

}  // namespace
}  // namespace palprig
