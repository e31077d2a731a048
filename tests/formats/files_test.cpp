// Every file the program reads is validated with file, field or line, and what was expected.
#include <gtest/gtest.h>

#include "formats/calibration_file.hpp"
#include "core/input_error.hpp"
#include "inputs/input_source.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/refusal.hpp"

using namespace palprig;
using palprig::test_support::TempDir;

namespace {
const std::filesystem::path kData = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";

const char* kGoodRig = R"({"version": 1, "id": "r1", "backend": "simulated",
  "safety": {"p_max_kPa": 50}, "plant": {"time_constant_s": 0.04}})";
}  // namespace

TEST(Files, ShippedFilesLoad) {
  const RigConfig rig = load_rig_file(kData / "rigs" / "simulated.json");
  EXPECT_EQ(rig.id, "sim-default");
  EXPECT_EQ(rig.safety.p_max_kPa, 60);
  EXPECT_EQ(rig.plants[2].time_constant_s, 0.05);
  const SceneFile scene = load_scene_file(kData / "scenes" / "phantom_abc.json");
  ASSERT_EQ(scene.tumors.size(), 3u);
  EXPECT_EQ(scene.tumors[1].name, "B");
  // Tumor B's centre is hard, the corner is soft.
  EXPECT_GT(scene.scene->sample({110, 50}, 2, 0).stiffness, 0.95);
  EXPECT_LT(scene.scene->sample({5, 5}, 2, 0).stiffness, 0.1);
  const CalibrationModels cal = load_calibration_file(kData / "calibration" / "paper002.json");
  EXPECT_NEAR(cal.actuators[0].pressure_for_stress_kPa(7.967), 11.75, 1e-9);
  const auto trace = load_trace_csv(kData / "traces" / "phantom_abc_pass.csv");
  EXPECT_GT(trace.size(), 1000u);
}

// A simulated regulator holds no air: the shipped simulated rigs ride out a 0.5 s stall of the
// machine (a demo or a rehearsal on a laptop or a shared virtual machine), while every rig file
// that drives hardware keeps the default 0.05 s, the regulator's time constant (docs/rig.md).
TEST(Files, OnlyTheSimulatedRigsAllowHalfASecondOfLostTime) {
  int simulated = 0, hardware = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kData / "rigs")) {
    const RigConfig rig = load_rig_file(entry.path());
    if (rig.backend == "simulated") {
      ++simulated;
      EXPECT_EQ(rig.safety.max_lost_time_s, 0.5) << entry.path();
    } else {
      ++hardware;
      EXPECT_EQ(rig.safety.max_lost_time_s, SafetyLimits{}.max_lost_time_s) << entry.path();
    }
  }
  EXPECT_EQ(simulated, 3);
  EXPECT_EQ(hardware, 4);
}

TEST(Files, RigFileFieldsAndDefaults) {
  TempDir dir;
  const RigConfig rig = load_rig_file(dir.write("rig.json", kGoodRig));
  EXPECT_EQ(rig.safety.p_max_kPa, 50);
  EXPECT_EQ(rig.plants[0].time_constant_s, 0.04);
  EXPECT_EQ(rig.plants[0].dead_time_s, PlantParams{}.dead_time_s);
  EXPECT_NE(rig.plants[0].seed, rig.plants[1].seed);  // independent noise per channel
  // Without the asymmetric keys the regulator is the symmetric one.
  EXPECT_FALSE(rig.plants[0].hysteresis_rising_kPa || rig.plants[0].hysteresis_falling_kPa ||
               rig.plants[0].exhaust_time_constant_s);
  EXPECT_EQ(rig.plants[0].exhaust_lag_factor_at_0, 1.0);
  EXPECT_EQ(rig.plants[0].gain_saturation_kPa, 0.0);
}

TEST(Files, AsymmetricRegulatorKeys) {
  const RigConfig rig = load_rig_file(kData / "rigs" / "simulated_asymmetric.json");
  EXPECT_EQ(rig.id, "sim-asymmetric");
  for (const PlantParams& p : rig.plants) {
    EXPECT_EQ(p.rising_play_kPa(), 3.0);
    EXPECT_EQ(p.falling_play_kPa(), 1.0);
    EXPECT_EQ(p.time_constant_s, 0.04);
    EXPECT_EQ(p.exhaust_time_constant(), 0.07);
    EXPECT_EQ(p.exhaust_lag_factor_at_0, 2.5);
    EXPECT_EQ(p.exhaust_lag_scale_kPa, 5.0);
    EXPECT_EQ(p.gain_saturation_kPa, 300.0);
  }
  TempDir dir;
  auto with_plant = [&](const std::string& plant) {
    const auto path = dir.write("asym.json", R"({"version": 1, "id": "r1", "plant": {)" + plant + "}}");
    return palprig::test_support::refusal([&] { load_rig_file(path); });
  };
  EXPECT_NE(with_plant(R"("hysteresis_rising_kPa": -1)").find("hysteresis_rising_kPa"), std::string::npos);
  EXPECT_NE(with_plant(R"("exhaust_lag_factor_at_0": 0.5)").find("exhaust_lag_factor_at_0"), std::string::npos);
  EXPECT_NE(with_plant(R"("gain_saturation_kPa": 0.5)").find("gain_saturation_kPa"), std::string::npos);
  EXPECT_EQ(with_plant(R"("hysteresis_falling_kPa": 0.5, "exhaust_time_constant_s": 0.1)"), "accepted");
}

TEST(Files, BadRigFilesAreRefusedWithFieldAndReason) {
  TempDir dir;
  auto rig = [&](const std::string& text) {
    const auto p = dir.write("rig.json", text);
    return palprig::test_support::refusal([&] { load_rig_file(p); });
  };
  const std::string f = (dir.path() / "rig.json").string();
  EXPECT_EQ(rig(R"({"id": "r"})"), f + ": version: a value (field is missing)");
  EXPECT_EQ(rig(R"({"version": 9, "id": "r"})"),
            f + ": version: version 1 or older (this palprig is older than the file), got 9");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "safety": {"p_max_kpa": 50}})"),
            f + ": safety.p_max_kPa: a value (field is missing)");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "safety": {"p_max_kPa": 50, "p_max_kpa": 5}})"),
            f + ": safety.p_max_kpa: no such field here (unknown field; check its spelling)");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "safety": {"p_max_kPa": -5}})"),
            f + ": safety.p_max_kPa: a number in 1..1000, got -5");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "plant": {"time_constant_s": "fast"}})"),
            f + ": plant.time_constant_s: a number in 0..10, got \"fast\"");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "backend": "usb"})"),
            f + ": backend: one of \"simulated\", \"modbus\", \"comedi\", got \"usb\"");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "channels": [{}, {}]})"),
            f + ": channels: exactly 3 channel objects, got 2");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "safety": {"p_max_kPa": 150}})"),
            f + ": safety.p_max_kPa: at most the regulators' max_kPa (100.000000)");
  EXPECT_EQ(rig(R"({"version": 1, "id": "r", "plant": {"min_kPa": 50, "max_kPa": 20}})"),
            f + ": plant.max_kPa: a value above min_kPa");
  EXPECT_EQ(rig("{\"version\": 1,\n \"id\": }"), f + ": at line 2, column 8: valid JSON (syntax error while parsing "
                                                     "value - unexpected '}'; expected '[', '{', or a literal)");
  EXPECT_EQ(palprig::test_support::refusal([&] { load_rig_file(dir.path() / "missing.json"); }),
            (dir.path() / "missing.json").string() +
                ": file: a regular file of at most 16 MiB holding a JSON document, got no such file");
}

TEST(Files, BadScenesAreRefused) {
  TempDir dir;
  dir.write("m.csv", "0,0.5\n1,0\n");
  auto scene = [&](const std::string& text) {
    const auto p = dir.write("s.json", text);
    return palprig::test_support::refusal([&] { load_scene_file(p); });
  };
  const std::string f = (dir.path() / "s.json").string();
  EXPECT_EQ(scene(R"({"version": 1, "map": {"file": "m.csv", "width_mm": 10, "height_mm": 10}})"), "accepted");
  EXPECT_EQ(scene(R"({"version": 1, "map": {"file": "m.csv", "width_mm": 0, "height_mm": 10}})"),
            f + ": map.width_mm: a number in 0.001..100000, got 0");
  EXPECT_EQ(scene(R"({"version": 1, "map": {"file": "m.csv", "width_mm": 10, "height_mm": 10, "sampling": "cubic"}})"),
            f + ": map.sampling: one of \"nearest\", \"bilinear\", got \"cubic\"");
  EXPECT_EQ(
      scene(
          R"({"version": 1, "map": {"file": "m.csv", "width_mm": 10, "height_mm": 10, "outside": {"background": 2}}})"),
      f + ": map.outside.background: a number in 0..1, got 2");
  EXPECT_EQ(scene(R"({"version": 1, "map": {"file": "nope.csv", "width_mm": 10, "height_mm": 10}})"),
            (dir.path() / "nope.csv").string() +
                ": file: a regular file of at most 256 MiB holding a stiffness map, got no such file");
  EXPECT_EQ(
      scene(
          R"({"version": 1, "map": {"file": "m.csv", "width_mm": 10, "height_mm": 10}, "tumors": [{"name": "A", "x_mm": 1, "y_mm": 1, "radius_mm": -2}]})"),
      f + ": tumors[0].radius_mm: a number in 0.001..10000, got -2");
  dir.write("bad.csv", "0,0.5\n1\n");
  EXPECT_EQ(scene(R"({"version": 1, "map": {"file": "bad.csv", "width_mm": 10, "height_mm": 10}})"),
            (dir.path() / "bad.csv").string() + ": line 2: 2 values like the first row, got 1");
}

TEST(Files, BadCalibrationIsRefused) {
  TempDir dir;
  auto cal = [&](const std::string& text) {
    const auto p = dir.write("c.json", text);
    return palprig::test_support::refusal([&] { load_calibration_file(p); });
  };
  const std::string f = (dir.path() / "c.json").string();
  const std::string ch = R"({"actuator": {"slope": 0.5, "intercept_kPa": 1}})";
  EXPECT_EQ(cal(R"({"version": 1, "rig_id": "*", "channels": [)" + ch + "," + ch + "]}"),
            f + ": channels: exactly 3 channels, got 2");
  EXPECT_EQ(
      cal(R"({"version": 1, "rig_id": "*", "channels": [)" + ch + "," + ch +
          R"(, {"actuator": {"slope": 0, "intercept_kPa": 1}}]})"),
      f + ": channels[2].actuator.slope: a positive stress-per-pressure slope (a flat or falling fit is degenerate)");
  EXPECT_EQ(
      cal(R"({"version": 1, "rig_id": "*", "channels": [)" + ch + "," + ch +
          R"(, {"actuator": {"slope": 1, "intercept_kPa": 1}, "hysteresis": {"linear_weight": 1, "thresholds_kPa": [1, 2], "weights": [0.1, -0.5]}}]})"),
      f + ": channels[2].hysteresis.weights: an invertible model: linear_weight > 0, weights >= 0, thresholds > 0 and "
          "increasing");
  const auto ok =
      dir.write("ok.json", R"({"version": 1, "rig_id": "bench-A", "channels": [)" + ch + "," + ch + "," + ch + "]}");
  const CalibrationModels c = load_calibration_file(ok);
  EXPECT_EQ(palprig::test_support::refusal([&] { check_calibration_matches(c, "bench-B", "rig.json"); }),
            ok.string() + ": rig_id: the id of the rig in use (\"bench-B\" from rig.json), got \"bench-A\"");
  EXPECT_EQ(palprig::test_support::refusal([&] { check_calibration_matches(c, "bench-A", "rig.json"); }), "accepted");
}

TEST(Files, BadTracesAreRefusedWithTheLine) {
  TempDir dir;
  auto trace = [&](const std::string& text) {
    const auto p = dir.write("t.csv", text);
    return palprig::test_support::refusal([&] { load_trace_csv(p); });
  };
  const std::string f = (dir.path() / "t.csv").string();
  EXPECT_EQ(trace("t,x,y,f\n0,0,0,0\n"), f + ": line 1: the header 't_s,x_mm,y_mm,force_N', got 't,x,y,f'");
  EXPECT_EQ(trace("t_s,x_mm,y_mm,force_N\n0,0,0,1\n0.1,0,zero,1\n"), f + ": line 3, y_mm: a finite number, got 'zero'");
  EXPECT_EQ(trace("t_s,x_mm,y_mm,force_N\n0,0,0,1\n0.1,0,0,-1\n"),
            f + ": line 3, force_N: a force >= 0 N, got -1.000000");
  EXPECT_EQ(trace("t_s,x_mm,y_mm,force_N\n0,0,0,1\n0,0,0,1\n"),
            f + ": line 3, t_s: a time after the previous row's 0.000000 s");
  EXPECT_EQ(trace("t_s,x_mm,y_mm,force_N\n0,0,0\n"), f + ": line 2: 4 values (t_s,x_mm,y_mm,force_N), got 3");
  EXPECT_EQ(trace("t_s,x_mm,y_mm,force_N\n0,0,0,1\n"), f + ": line 2: at least 2 samples");
  EXPECT_EQ(trace("t_s,x_mm,y_mm,force_N\n0,0,0,1\n0.1,inf,0,1\n"), f + ": line 3, x_mm: a finite number, got 'inf'");
}

TEST(TraceInput, InterpolatesAndLiftsAtTheEnd) {
  TraceInput in({{0, 0, 0, 2, true}, {1, 10, 20, 4, true}}, "t");
  const TouchSample s = in.latest(0.25);
  EXPECT_NEAR(s.x_mm, 2.5, 1e-12);
  EXPECT_NEAR(s.y_mm, 5.0, 1e-12);
  EXPECT_NEAR(s.force_N, 2.5, 1e-12);
  EXPECT_TRUE(s.in_contact);
  EXPECT_FALSE(in.latest(1.5).in_contact);
  EXPECT_EQ(in.latest(1.5).force_N, 0.0);
  EXPECT_NEAR(in.latest(0.5).x_mm, 5.0, 1e-12);  // going back in time restarts the search
}

TEST(RasterInput, CoversTheSceneRowByRow) {
  RasterInput sweep({0, 0, 100, 50}, RasterPlan{50.0, 10.0, 2.0, 5.0});
  // Rows at y = 5, 15, 25, 35, 45, each 90 mm long.
  EXPECT_NEAR(sweep.duration_s(), (5 * 90 + 4 * 10) / 50.0, 1e-12);
  EXPECT_NEAR(sweep.latest(0).x_mm, 5, 1e-12);
  EXPECT_NEAR(sweep.latest(1.8).x_mm, 95, 1e-12);  // end of the first row
  EXPECT_NEAR(sweep.latest(2.0).y_mm, 15, 1e-12);  // stepped down
  EXPECT_NEAR(sweep.latest(2.2).x_mm, 85, 1e-12);  // coming back
  EXPECT_TRUE(sweep.latest(1.0).in_contact);
  EXPECT_FALSE(sweep.latest(sweep.duration_s() + 1).in_contact);
}
