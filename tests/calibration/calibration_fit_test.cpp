// From sweep data to the calibration file: the fig. 8 tables recover known branch lines, the
// checks refuse bad sweeps with the line and channel, and the written file is what the
// controller loads (and refuses when degenerate).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "controller/tick_setup.hpp"
#include "calibration/calibration_fit.hpp"
#include "calibration/calibration_writer.hpp"
#include "formats/rig_file.hpp"
#include "core/input_error.hpp"
#include "tests/support/refusal.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::refusal;
using palprig::test_support::TempDir;

namespace {

// A regulator with gain, offset and a backlash of half-width h (monitor lands h below the
// command on inflation, h above on deflation; commanded towards 0 kPa its exhaust empties it, so
// the band above the command narrows to the command, as palprig's simulated plant and the tick's
// model do), optionally a sensor at 0.01 mm/kPa.
struct SyntheticRig {
  double gain = 1.0, offset_kPa = 0.0, half_gap_kPa = 2.0, noise_sd = 0.02;
  bool sensor = false;
  std::mt19937 rng{5};
  std::array<double, kFingerCount> play{};
  std::size_t line = 10;

  HoldPoint read(int channel, double command, SweepSegment seg, int repeat, SweepBranch branch) {
    std::normal_distribution<double> noise(0, noise_sd);
    double& z = play[std::size_t(channel - 1)];
    z = std::clamp(z, command - half_gap_kPa, command + std::min(half_gap_kPa, std::max(command, 0.0)));
    HoldPoint p;
    p.channel = channel;
    p.segment = seg;
    p.repeat = repeat;
    p.branch = branch;
    p.command_kPa = command;
    p.monitor_kPa = gain * z + offset_kPa + noise(rng);
    if (sensor) p.sensor = 0.01 * p.monitor_kPa;
    p.samples = 30;
    p.line = line++;
    return p;
  }

  // Paper 002 staircase 10..60 kPa, `repeats` times, then random levels for the PI fit.
  SweepData sweep(const std::vector<int>& channels, int repeats = 5, int random_levels = 80) {
    SweepData d;
    d.file = "DATA.csv";
    d.info.rig_id = "bench-3";
    d.has_monitor = true;
    d.has_sensor = sensor;
    d.channels = channels;
    std::mt19937 pick(9);
    std::uniform_real_distribution<double> level(10, 60);
    for (int c : channels) {
      for (int r = 1; r <= repeats; ++r) {
        d.points.push_back(read(c, 0, SweepSegment::vent, 0, SweepBranch::none));
        for (int l = 10; l <= 60; l += 10)
          d.points.push_back(read(c, l, SweepSegment::staircase, r, SweepBranch::inflation));
        for (int l = 60; l >= 10; l -= 10)
          d.points.push_back(read(c, l, SweepSegment::staircase, r, SweepBranch::deflation));
      }
      for (int k = 0; k < random_levels; ++k)
        d.points.push_back(read(c, level(pick), SweepSegment::random, 0, SweepBranch::none));
    }
    return d;
  }
};

CalibrationFitOptions options() {
  CalibrationFitOptions o;
  o.date = "2026-11-22T12:00:00Z";
  return o;
}

}  // namespace

TEST(CalibrationFit, BranchTablesRecoverTheRegulatorsLines) {
  SyntheticRig rig;
  rig.gain = 0.98;
  rig.offset_kPa = 0.5;
  rig.half_gap_kPa = 1.5;
  const CalibrationResult r = fit_calibration(rig.sweep({1, 2, 3}), options());
  for (const auto& ch : r.channels) {
    ASSERT_TRUE(ch.regulator) << ch.channel;
    const BranchFits& f = *ch.regulator;
    // Off the top level (where deflation starts without a reversal) the branches are the
    // command shifted by -/+ the half gap, through the gain and offset.
    EXPECT_NEAR(f.inflation.slope, 0.98, 0.002);
    EXPECT_NEAR(f.inflation.intercept, 0.5 - 0.98 * 1.5, 0.05);
    EXPECT_GT(f.inflation.r_squared, 0.9999);
    EXPECT_LT(f.deflation.r_squared, f.inflation.r_squared);  // the top level sits on the other branch
    EXPECT_EQ(f.both.n, 60u);
    EXPECT_EQ(f.levels, 6u);
    EXPECT_EQ(f.repeats, 5u);
    // Five of six levels are 2 * 1.5 * gain apart, the top level 0 apart.
    EXPECT_NEAR(f.gap, 5.0 / 6.0 * 2 * 1.5 * 0.98, 0.02);
    EXPECT_LT(f.repeat_sd_percent, 1.0);
    ASSERT_TRUE(ch.regulator_check);
    EXPECT_TRUE(ch.regulator_check->passed());
  }
  ASSERT_TRUE(r.pooled_regulator);
  EXPECT_EQ(r.pooled_regulator->both.n, 180u);
  EXPECT_FALSE(r.pooled_response);
}

TEST(CalibrationFit, HysteresisModelOfEachChannelTracksItsRegulator) {
  SyntheticRig rig;
  const CalibrationResult r = fit_calibration(rig.sweep({1, 2, 3}), options());
  for (const auto& ch : r.channels) {
    ASSERT_TRUE(ch.hysteresis);
    EXPECT_EQ(ch.hysteresis_source, HysteresisSource::monitor);
    EXPECT_TRUE(ch.hysteresis->converged);
    EXPECT_LT(ch.hysteresis->rms_error_kPa, 0.05);  // noise 0.02 + the 1 % linear floor
    // The model's loop is as wide as the regulator's: from 30 up vs from 30 down.
    PrandtlIshlinskii m = ch.hysteresis->model;
    m.reset(0);
    m.apply(60);
    const double down = m.apply(30);
    m.apply(0);
    const double up = m.apply(30);
    EXPECT_NEAR(down - up, 4.0, 0.1);
  }
}

TEST(CalibrationFit, WrittenFileIsWhatTheControllerLoads) {
  TempDir dir;
  SyntheticRig rig;
  CalibrationFitOptions o = options();
  o.force_window = ForceWindowFit{{1.1, 2.6, 60, 120}, 0.05, 0.1, 3, 3};
  o.stress_pairs = {{0, 0, 5.0}, {0, 10, 7.5}, {0, 20, 10.0}, {2, 0, 5.0}, {2, 10, 8.0}, {2, 20, 11.0}};
  o.stress_file = "fe.csv";
  const CalibrationResult r = fit_calibration(rig.sweep({1, 2}), o);  // channel 3 not swept
  const auto path = dir.path() / "cal.json";
  const CalibrationModels cal = write_calibration_file(path, calibration_json(r));
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename(), "cal.json") << "a temporary file was left beside it";
  const CalibrationModels again = load_calibration_file(path);
  EXPECT_EQ(again.rig_id, "bench-3");
  for (std::size_t c = 0; c < 2; ++c) {
    const PrandtlIshlinskii& want = r.channels[c].hysteresis->model;
    ASSERT_EQ(again.hysteresis[c].operator_count, want.operator_count);
    EXPECT_DOUBLE_EQ(again.hysteresis[c].linear_weight, want.linear_weight);
    for (std::size_t i = 0; i < want.operator_count; ++i) {
      EXPECT_DOUBLE_EQ(again.hysteresis[c].thresholds_kPa[i], want.thresholds_kPa[i]);
      EXPECT_DOUBLE_EQ(again.hysteresis[c].weights[i], want.weights[i]);
    }
  }
  EXPECT_TRUE(again.hysteresis[2].is_identity());
  EXPECT_NEAR(again.actuators[0].slope, 0.25, 1e-9);   // shared pairs
  EXPECT_NEAR(again.actuators[1].slope, 0.275, 1e-9);  // shared + channel 2's own
  EXPECT_NEAR(again.actuators[2].slope, 0.25, 1e-9);
  ASSERT_TRUE(again.force_window);
  EXPECT_DOUBLE_EQ(again.force_window->f_min_N, 1.1);
  EXPECT_DOUBLE_EQ(again.force_window->f_max_N, 2.6);
  EXPECT_EQ(cal.source, path.string());
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n == "channel 3 was not swept: no hysteresis model (identity)";
  EXPECT_TRUE(noted);
  // The tick gets each fitted model, which it inverts.
  RigConfig rig_config;
  const TickConfig tick = make_tick_config(rig_config, again);
  PrandtlIshlinskii model = again.hysteresis[0], inverse = tick.hysteresis_model[0].inverse();
  model.reset(0);
  inverse.reset(0);
  for (double t : {10.0, 25.0, 18.0, 40.0, 12.0, 33.0}) EXPECT_NEAR(model.apply(inverse.apply(t)), t, 1e-9);
}

TEST(CalibrationFit, ChannelsWithoutStressPairsKeepTheBaseLine) {
  SyntheticRig rig;
  CalibrationFitOptions o = options();
  o.stress_pairs = {{3, 0, 5.0}, {3, 10, 8.0}, {3, 20, 11.0}};
  o.stress_file = "pairs.csv";
  const CalibrationResult r = fit_calibration(rig.sweep({1}), o);
  EXPECT_NEAR(r.channels[2].actuator.slope, 0.3, 1e-12);
  EXPECT_FALSE(r.channels[0].stress_line);
  EXPECT_DOUBLE_EQ(r.channels[0].actuator.slope, ActuatorModel{}.slope);
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n == "channel 1 has no stress pairs: its actuator line is the base's";
  EXPECT_TRUE(noted);
  o.stress_pairs.pop_back();  // two pairs for channel 3: too few for a line
  EXPECT_EQ(refusal([&] { fit_calibration(rig.sweep({1}), o); }),
            "pairs.csv: stress line of channel 3: at least 3 points for a line, got 2");
}

// Without --stress pairs the note said "actuator stress lines from (built-in paper 002 defaults)
// (no --stress pairs)": it now says in words where the lines come from, and a file given with
// --base by its name.
TEST(CalibrationFit, TheNoteSaysWhereTheActuatorLinesComeFrom) {
  SyntheticRig rig;
  const CalibrationResult built_in = fit_calibration(rig.sweep({1}), options());
  bool noted = false;
  for (const auto& n : built_in.notes) {
    EXPECT_EQ(n.find("(built-in"), std::string::npos) << n;
    noted = noted || n == "actuator stress lines kept from paper 002's regression (no --stress pairs given)";
  }
  EXPECT_TRUE(noted);
  CalibrationFitOptions o = options();
  o.base.source = "lab_rig.json";
  const CalibrationResult based = fit_calibration(rig.sweep({1}), o);
  noted = false;
  for (const auto& n : based.notes)
    noted = noted || n == "actuator stress lines kept from lab_rig.json (no --stress pairs given)";
  EXPECT_TRUE(noted);
}

TEST(CalibrationFit, SensorTablesAndHysteresisFromTheSensor) {
  SyntheticRig rig;
  rig.sensor = true;
  CalibrationFitOptions o = options();
  o.hysteresis_from = HysteresisSource::sensor;
  const CalibrationResult r = fit_calibration(rig.sweep({1, 2, 3}), o);
  ASSERT_TRUE(r.channels[0].response);
  EXPECT_NEAR(r.channels[0].response->inflation.slope, 0.01, 1e-4);
  EXPECT_NEAR(r.channels[0].response->gap, 0.01 * 5.0 / 6.0 * 4.0, 5e-4);
  ASSERT_TRUE(r.pooled_response);
  EXPECT_EQ(r.channels[0].hysteresis_source, HysteresisSource::sensor);
  EXPECT_LT(r.channels[0].hysteresis->rms_error_kPa, 0.1);
}

TEST(CalibrationFit, RefusesBadSweepsNamingTheLineAndChannel) {
  {
    SyntheticRig rig;
    SweepData d = rig.sweep({1, 2});
    // A leak: channel 2's monitor falls while the inflation command rises.
    for (auto& p : d.points)
      if (p.channel == 2 && p.repeat == 3 && p.branch == SweepBranch::inflation && p.command_kPa == 40)
        p.monitor_kPa = 20;
    const std::string m = refusal([&] { fit_calibration(d, options()); });
    EXPECT_EQ(m.rfind("DATA.csv: line ", 0), 0u) << m;
    EXPECT_NE(
        m.find(
            "(channel 2, repeat 3 inflation, 40 kPa): a monotone monitor along the inflation staircase of channel 2: "
            "it fell from 28 to 20 while the command went from 30 to 40 kPa"),
        std::string::npos)
        << m;
    EXPECT_NE(m.find("non-monotone sweep"), std::string::npos) << m;
  }
  {
    SyntheticRig rig;
    rig.gain = 0.8;  // regulator without enough supply: about 13 kPa short at 60
    EXPECT_EQ(
        refusal([&] { fit_calibration(rig.sweep({1}), options()); }),
        "DATA.csv: channel 1 regulator: a monitor within 3.0 kPa of the command; its line monitor = 0.777 * command + "
        "0.54 kPa is off by 12.84 kPa at 60.0 kPa (check the regulator's supply, range and scaling, or raise "
        "`regulator_tolerance_kPa`)");
    CalibrationFitOptions lax = options();
    lax.regulator_tolerance_kPa = 15;
    EXPECT_EQ(refusal([&] { fit_calibration(rig.sweep({1}), lax); }), "accepted");
  }
  {
    SyntheticRig rig;
    rig.sensor = true;
    SweepData d = rig.sweep({1});
    for (auto& p : d.points) p.sensor = 0.0;
    EXPECT_EQ(
        refusal([&] { fit_calibration(d, options()); }),
        "DATA.csv: channel 1 sensor: a sensor that moves with the command; it never moved (all 145 readings are 0): "
        "check its wiring, supply and scaling");
  }
  {
    SyntheticRig rig;
    SweepData d = rig.sweep({1});
    d.info.rig_id.clear();
    EXPECT_EQ(refusal([&] { fit_calibration(d, options()); }),
              "DATA.csv: rig_id: the rig the data came from (a \"# rig_id: ...\" line, or `rig_id`)");
    CalibrationFitOptions named = options();
    named.rig_id = "bench-9";
    EXPECT_EQ(fit_calibration(d, named).rig_id, "bench-9");
    named.rig_id = "*";
    EXPECT_EQ(refusal([&] { fit_calibration(d, named); }),
              "DATA.csv: rig_id: a real rig id: a fitted calibration belongs to one rig, not \"*\"");
  }
  {
    SyntheticRig rig;
    SweepData d = rig.sweep({1}, 1, 0);  // one staircase: 13 holds, not enough for 8 operators
    EXPECT_EQ(
        refusal([&] { fit_calibration(d, options()); }),
        "DATA.csv: channel 1 hysteresis: at least 68 quasi-static samples for 8 play operators, got 13 (record more "
        "holds or use fewer operators)");
  }
}

TEST(CalibrationFit, AFitCeresDidNotConvergeOnIsReportedAsSuch) {
  SyntheticRig rig;
  CalibrationFitOptions o = options();
  o.hysteresis.max_iterations = 1;
  const std::string m = refusal([&] { fit_calibration(rig.sweep({1}), o); });
  EXPECT_EQ(m.rfind("DATA.csv: channel 1 hysteresis: a fit Ceres converges on; it did not (Ceres Solver Report: ", 0),
            0u)
      << m;
  EXPECT_NE(m.find("Termination: NO_CONVERGENCE"), std::string::npos) << m;
}

TEST(CalibrationFile, RefusesDegenerateHysteresisAndBadForceWindows) {
  TempDir dir;
  const std::string ch = R"({"actuator": {"slope": 0.25, "intercept_kPa": 5}})";
  auto load = [&](const std::string& channel3, const std::string& extra) {
    const auto p = dir.write("c.json", R"({"version": 1, "rig_id": "r", "channels": [)" + ch + "," + ch + "," +
                                           channel3 + "]" + extra + "}");
    return refusal([&] { load_calibration_file(p); });
  };
  const std::string f = (dir.path() / "c.json").string();
  EXPECT_EQ(
      load(R"({"actuator": {"slope": 0.25, "intercept_kPa": 5}, "hysteresis": {"linear_weight": 0.01,
                   "thresholds_kPa": [2], "weights": [0.05]}})",
           ""),
      f + ": channels[2].hysteresis.weights: a model of gain near 1 (linear_weight + sum of weights in 0.2..5), got "
          "0.060000");
  EXPECT_EQ(load(ch, R"(, "force_window": {"f_min_N": 2, "f_max_N": 1})"),
            f + ": force_window.f_max_N: a force above f_min_N (the systolic press above the diastolic)");
  EXPECT_EQ(load(ch, R"(, "force_window": {"f_min_N": 1, "f_max_N": 2, "fmax": 3})"),
            f + ": force_window.fmax: no such field here (unknown field; check its spelling)");
  EXPECT_EQ(load(ch, R"(, "force_window": {"f_min_N": 1, "f_max_N": 2, "presses_min": 3})"), "accepted");
  // The shipped paper 002 calibration stays valid.
  EXPECT_NO_THROW(load_calibration_file(std::string(PALPRIG_SOURCE_DIR) + "/data/calibration/paper002.json"));
}
