// Values the readers took although the rig could render nothing sensible with them (safety
// still clamped): a tumor 65 m off the map, an actuator intercept of 1e5 kPa (every target
// pressure 0 kPa), a falling line in the calibration's fit tables. Each is refused at load with
// one line naming the file, the field and the range expected.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "formats/calibration_file.hpp"
#include "formats/scene_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/refusal.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {

std::string data(const std::string& rel) { return std::string(PALPRIG_SOURCE_DIR) + "/data/" + rel; }

nlohmann::json read_json(const std::string& path) {
  return nlohmann::json::parse(palprig::test_support::read_file(path));
}

}  // namespace

TEST(AbsurdValues, ATumorOffTheMapIsRefused) {
  TempDir dir;
  dir.write("m.csv", "0,0.5\n1,0\n");
  auto scene = [&](double x, double y) {
    nlohmann::json s = {{"version", 1},
                        {"map", {{"file", "m.csv"}, {"width_mm", 160}, {"height_mm", 120}}},
                        {"tumors", {{{"name", "A"}, {"x_mm", x}, {"y_mm", y}, {"radius_mm", 4}}}}};
    const auto p = dir.write("s.json", s.dump());
    return palprig::test_support::refusal([&] { load_scene_file(p); });
  };
  const std::string f = (dir.path() / "s.json").string();
  EXPECT_EQ(scene(65000, 40), f + ": tumors[0].x_mm: a number in 0..160, got 65000.0");
  EXPECT_EQ(scene(40, -3), f + ": tumors[0].y_mm: a number in 0..120, got -3.0");
  EXPECT_EQ(scene(160, 120), "accepted");
  EXPECT_EQ(palprig::test_support::refusal([&] { load_scene_file(data("scenes/phantom_abc.json")); }), "accepted");
}

TEST(AbsurdValues, AFunctionSceneTumorOffTheBodyIsRefused) {
  TempDir dir;
  nlohmann::json s = read_json(data("scenes/phantom_abc_function.json"));
  ASSERT_TRUE(s.contains("inclusions"));
  int tumor = -1;
  for (std::size_t i = 0; i < s["inclusions"].size() && tumor < 0; ++i)
    if (s["inclusions"][i].value("kind", "tumor") == "tumor" && s["inclusions"][i]["shape"].contains("centre_mm"))
      tumor = static_cast<int>(i);
  ASSERT_GE(tumor, 0);
  EXPECT_EQ(palprig::test_support::refusal([&] { load_scene_file(dir.write("ok.json", s.dump())); }), "accepted");
  s["inclusions"][tumor]["shape"]["centre_mm"][0] = 6500;  // 6.5 m: within the shape bound (10 m), far off the body
  const auto f = dir.write("far.json", s.dump());
  const std::string why = palprig::test_support::refusal([&] { load_scene_file(f); });
  EXPECT_EQ(why.rfind(f.string() + ": inclusions[" + std::to_string(tumor) +
                          "].shape: a tumor centred on the body (x in 0..160 mm, y in 0..120 mm), got '",
                      0),
            0u)
      << why;
  EXPECT_NE(why.find("at (6500, "), std::string::npos) << why;
}

TEST(AbsurdValues, ActuatorLinesThatRenderNothingAreRefused) {
  TempDir dir;
  auto cal = [&](const std::string& actuator, const std::string& extra = "") {
    const std::string ok = R"({"actuator": {"slope": 0.25, "intercept_kPa": 4.99}})";
    const auto p = dir.write("c.json", R"({"version": 1, "rig_id": "*", "channels": [)" + ok + "," + ok + "," +
                                           actuator + "]" + extra + "}");
    return palprig::test_support::refusal([&] { load_calibration_file(p); });
  };
  const std::string f = (dir.path() / "c.json").string();
  EXPECT_EQ(
      cal(R"({"actuator": {"slope": 0.25, "intercept_kPa": 100000}})"),
      f + ": channels[2].actuator.intercept_kPa: the stress of the uninflated actuator in -1000..7.967 kPa (below "
          "the stress model's hard_stress_kPa, or every target is 0 kPa), got 100000");
  EXPECT_EQ(cal(R"({"actuator": {"slope": 0.25, "intercept_kPa": 9}})",
                R"(, "stress_model": {"soft_stress_kPa": 5, "hard_stress_kPa": 10, "reference_force_N": 2})"),
            "accepted");
  EXPECT_EQ(cal(R"({"actuator": {"slope": 5000, "intercept_kPa": 1}})"),
            f + ": channels[2].actuator.slope: a stress-per-pressure slope of at most 1000 kPa per kPa, got 5000");
  EXPECT_EQ(palprig::test_support::refusal([&] { load_calibration_file(data("calibration/sim-default.json")); }),
            "accepted");
  EXPECT_EQ(palprig::test_support::refusal([&] { load_calibration_file(data("calibration/paper002.json")); }),
            "accepted");
}

TEST(AbsurdValues, AFallingLineInTheFitTablesIsRefused) {
  TempDir dir;
  nlohmann::json c = read_json(data("calibration/sim-default.json"));
  c["fits"]["channels"][1]["regulator"]["inflation"]["slope"] = -0.98;
  const auto f = dir.write("neg.json", c.dump());
  EXPECT_EQ(palprig::test_support::refusal([&] { load_calibration_file(f); }),
            f.string() +
                ": fits.channels[1].regulator.inflation.slope: a rising fit line: a slope in 1e-09..1000 (a flat "
                "or falling fit is degenerate), got -0.98");
  c = read_json(data("calibration/sim-default.json"));
  c["fits"]["channels"][0]["stress_line"]["r_squared"] = 3;
  const auto g = dir.write("r2.json", c.dump());
  EXPECT_EQ(palprig::test_support::refusal([&] { load_calibration_file(g); }),
            g.string() + ": fits.channels[0].stress_line.r_squared: an R^2 of at most 1, got 3");
  // A figure that does not exist is null (JSON has no NaN) and is accepted.
  c = read_json(data("calibration/sim-default.json"));
  c["fits"]["channels"][0]["stress_line"]["residual_sd"] = nullptr;
  EXPECT_EQ(palprig::test_support::refusal([&] { load_calibration_file(dir.write("null.json", c.dump())); }),
            "accepted");
}

// A calibration with x_max_kPa 1.8e19 read as valid (attack round 4): every figure of the fit
// tables is bounded, a line's pressure range by a regulator's, with the field and the range.
TEST(AbsurdValues, AbsurdFiguresInTheFitTablesAreRefusedWithTheRangeExpected) {
  TempDir dir;
  nlohmann::json c = read_json(data("calibration/sim-default.json"));
  c["fits"]["channels"][0]["regulator"]["inflation"]["x_max_kPa"] = 1.8e19;
  const auto f = dir.write("xmax.json", c.dump());
  EXPECT_EQ(
      palprig::test_support::refusal([&] { load_calibration_file(f); }),
      f.string() + ": fits.channels[0].regulator.inflation.x_max_kPa: a pressure in -1e+04..1e+04 kPa, got 1.8e+19");
  c = read_json(data("calibration/sim-default.json"));
  c["fits"]["channels"][0]["regulator"]["inflation"]["x_min_kPa"] = 90;
  c["fits"]["channels"][0]["regulator"]["inflation"]["x_max_kPa"] = 10;
  const auto h = dir.write("order.json", c.dump());
  EXPECT_EQ(palprig::test_support::refusal([&] { load_calibration_file(h); }),
            h.string() + ": fits.channels[0].regulator.inflation.x_max_kPa: a pressure at or above x_min_kPa, got 10");
  c = read_json(data("calibration/sim-default.json"));
  c["fits"]["channels"][2]["hysteresis_fit"]["solve_seconds"] = 3e15;
  const auto k = dir.write("seconds.json", c.dump());
  EXPECT_NE(palprig::test_support::refusal([&] {
              load_calibration_file(k);
            }).find("fits.channels[2].hysteresis_fit.solve_seconds: a figure within"),
            std::string::npos);
}
