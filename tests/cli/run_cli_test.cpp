// The main job through the real palprig program: replay end to end, bad files refused with
// exit 2 before anything moves, and the demo.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/run_process.hpp"
#include "tests/support/text_and_paths.hpp"

using namespace palprig::test_support;

namespace {}  // namespace

TEST(RunCommand, ReplayOfTheBundledTraceGivesTheSummaryAsJson) {
  TempDir dir;
  const auto telemetry = dir.path() / "tel.csv";
  const ProcessResult r =
      run_process(palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/phantom_abc.json") +
                  " --input trace:" + palprig::testing::shipped_data("traces/phantom_abc_pass.csv") + " --rig " +
                  palprig::testing::shipped_data("rigs/simulated.json") +
                  " --rate-hz 1000 --replay --json --telemetry " + telemetry.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ticks"], 13290);  // the trace lasts 13.29 s
  EXPECT_EQ(j["overruns"], 0);
  EXPECT_TRUE(j["fault"].is_null());
  EXPECT_NEAR(j["target_kPa"][0]["max"].get<double>(), 11.75, 0.01);  // the pen passes over tumor centres
  EXPECT_LE(j["setpoint_kPa"][0]["max"].get<double>(), 60.0);
  EXPECT_GT(j["plant_kPa"][0]["max"].get<double>(), 8.0);
  EXPECT_EQ(j["telemetry"], telemetry.string());
  // One CSV row per tick plus the header.
  const std::string tel = read_file(telemetry);
  EXPECT_EQ(std::count(tel.begin(), tel.end(), '\n'), 13291);
}

TEST(RunCommand, TextSummaryNamesTicksFingersAndFaults) {
  const ProcessResult r =
      run_process(palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/phantom_abc.json") +
                  " --input sweep --duration-s 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2000 ticks at 1000 Hz"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("finger   target kPa"), std::string::npos);
  EXPECT_NE(r.out.find("faults: none"), std::string::npos);
}

// The pen raster is `--input sweep` on the command line (kept) and `raster` too (its name in code;
// "sweep" is calibration's staircase). Both give the same run.
TEST(RunCommand, RasterInputIsAcceptedUnderBothNames) {
  const std::string base = palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/phantom_abc.json") +
                           " --duration-s 2 --json";
  const ProcessResult sweep = run_process(base + " --input sweep");
  const ProcessResult raster = run_process(base + " --input raster");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  ASSERT_EQ(raster.exit_code, 0) << raster.err;
  const auto a = nlohmann::json::parse(sweep.out), b = nlohmann::json::parse(raster.out);
  EXPECT_EQ(a["ticks"], 2000);
  EXPECT_EQ(a["target_kPa"], b["target_kPa"]);
  EXPECT_EQ(a["setpoint_kPa"], b["setpoint_kPa"]);
}

TEST(RunCommand, BadFilesStopBeforeAnythingMovesWithExitTwo) {
  TempDir dir;
  const auto bad_rig = dir.write("rig.json", R"({"version": 1, "id": "x", "safety": {"p_max_kPa": 5000}})");
  const auto telemetry = dir.path() / "never.csv";
  ProcessResult r =
      run_process(palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/phantom_abc.json") +
                  " --rig " + bad_rig.string() + " --telemetry " + telemetry.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: " + bad_rig.string() + ": safety.p_max_kPa: a number in 1..1000, got 5000\n");
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(std::filesystem::exists(telemetry));  // nothing started

  const auto bad_trace = dir.write("t.csv", "t_s,x_mm,y_mm,force_N\n0,1,1,1\n0.5,2,2,nan\n");
  r = run_process(palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/phantom_abc.json") +
                  " --input trace:" + bad_trace.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "palprig: " + bad_trace.string() + ": line 3, force_N: a finite number, got 'nan'\n");

  r = run_process(palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/phantom_abc.json") +
                  " --input joystick");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "palprig: --input: joystick: trace:FILE, sweep, tablet, tablet:/dev/input/eventN, tablet:FILE.evemu or "
            "igtl:HOST:PORT\n");
}

TEST(DemoCommand, TumorsFeelHarderThanSoftTissue) {
  TempDir dir;
  const ProcessResult r = run_process(palprig_bin() + " demo --json --out " + dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["tumors_feel_harder"].get<bool>());
  ASSERT_EQ(j["regions"].size(), 4u);
  const double soft = j["regions"][3]["target_kPa_mean"];
  for (int t = 0; t < 3; ++t) EXPECT_GT(j["regions"][t]["target_kPa_mean"].get<double>(), soft + 5.0);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "telemetry.csv"));
}

TEST(RunCommand, CompensateLagNeedsIdentifiedDynamicsAndSaysWhatItDoes) {
  const std::string base = palprig_bin() + " run --scene " + palprig::testing::shipped_data("scenes/phantom_abc.json") +
                           " --input trace:" + palprig::testing::shipped_data("traces/phantom_abc_pass.csv") +
                           " --duration-s 3 --json";
  // paper 002's models have no identified dynamics: refused before anything moves.
  const ProcessResult none =
      run_process(base + " --cal " + palprig::testing::shipped_data("calibration/paper002.json") + " --compensate-lag");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_EQ(none.out, "");
  EXPECT_NE(none.err.find("paper002.json: lag_compensation: identified regulator dynamics (channels[].dynamics) for "
                          "--compensate-lag"),
            std::string::npos)
      << none.err;
  // The simulated rig's calibration has them: on, said per channel, and the setpoints differ
  // from the same run without (`--no-compensate-lag`, the file's own default).
  const ProcessResult on = run_process(
      base + " --cal " + palprig::testing::shipped_data("calibration/sim-default.json") + " --compensate-lag");
  ASSERT_EQ(on.exit_code, 0) << on.err;
  EXPECT_NE(on.err.find("palprig: lag compensation on for channels 1 (dead time"), std::string::npos) << on.err;
  const ProcessResult off = run_process(
      base + " --cal " + palprig::testing::shipped_data("calibration/sim-default.json") + " --no-compensate-lag");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_EQ(off.err.find("lag compensation"), std::string::npos) << off.err;
  const auto a = nlohmann::json::parse(on.out), b = nlohmann::json::parse(off.out);
  EXPECT_EQ(a["target_kPa"], b["target_kPa"]);  // the models ask the same
  EXPECT_NE(a["setpoint_kPa"], b["setpoint_kPa"]);
  EXPECT_LE(a["setpoint_kPa"][0]["max"].get<double>(), 60.0);
}

TEST(DemoCommand, WithLagCompensationTheTumorsArriveNearerTheirTarget) {
  TempDir dir;
  const std::string base = palprig_bin() + " demo --json --out " + dir.path().string();
  const ProcessResult plain =
      run_process(base + " --cal " + palprig::testing::shipped_data("calibration/sim-default.json"));
  const ProcessResult comp = run_process(base + " --compensate-lag");  // the simulated rig's calibration
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(comp.exit_code, 0) << comp.err;
  EXPECT_NE(comp.err.find("lag compensation on"), std::string::npos) << comp.err;
  const auto p = nlohmann::json::parse(plain.out), c = nlohmann::json::parse(comp.out);
  for (int t = 0; t < 3; ++t) {
    const double target = c["regions"][t]["target_kPa_mean"];
    EXPECT_EQ(p["regions"][t]["target_kPa_mean"].get<double>(), target);
    EXPECT_GT(c["regions"][t]["plant_kPa_mean"].get<double>(), p["regions"][t]["plant_kPa_mean"].get<double>()) << t;
    EXPECT_NEAR(c["regions"][t]["plant_kPa_mean"].get<double>() / target, 1.0, 0.05) << t;
  }
}
