// The regulators' dynamics from the sweep's step and chirp rows: the sweep records them at the
// loop's rate with the setpoint actually sent, the fit recovers a simulated plant's dead time and
// lag (with its play through the hysteresis model), reports R^2 and residuals per excitation, a
// poorly fitting channel is marked and keeps lag compensation off, and the calibration file
// carries the dynamics and the lag_compensation section (and refuses them when impossible).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "calibration/calibration_fit.hpp"
#include "calibration/calibration_writer.hpp"
#include "calibration/dynamics_fit.hpp"
#include "calibration/sweep_csv.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_runner.hpp"
#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "core/input_error.hpp"
#include "rigs/simulated_rig.hpp"
#include "tests/support/refusal.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;
using palprig::test_support::refusal;
using palprig::test_support::TempDir;

namespace {

// A sweep of the documented recipe on a simulated rig with the given plant, written to a file
// and read back as `calibrate fit` reads it.
SweepData recorded_sweep(const TempDir& dir, const PlantParams& plant, const std::string& excitation = "all") {
  std::array<PlantParams, kFingerCount> plants{plant, plant, plant};
  SimulatedRig rig(plants, 60);
  rig.open();
  SweepPlanOptions plan;
  plan.staircase = plan.random = plan.sine = excitation == "all";
  plan.step = plan.chirp = true;
  const SweepSchedule schedule = plan_calibration_sweep(plan, 60);
  SweepRunOptions run;
  run.realtime = false;
  SweepFileInfo info;
  info.rig_id = "sim-test";
  info.backend = "simulated";
  info.rate_hz = run.rate_hz;
  const auto path = dir.path() / ("sweep-" + excitation + ".csv");
  SweepCsvWriter writer(path, info, run.channels);
  palprig::testing::LeasedRig leased1(rig);
  const SweepOutcome out = run_calibration_sweep(leased1.lease, schedule, run, writer);
  writer.finish(out);
  EXPECT_FALSE(out.faulted) << out.fault;
  EXPECT_EQ(out.holds_unsettled, 0u);  // timed holds are not "unsettled"
  return read_sweep_csv(path);
}

}  // namespace

TEST(DynamicsSweep, StepAndChirpAreRecordedAtTheLoopsRateWithTheSetpointSent) {
  const SweepSchedule plan = [] {
    SweepPlanOptions o;
    o.staircase = false;
    o.step = o.chirp = true;
    return plan_calibration_sweep(o, 60);
  }();
  std::size_t steps = 0, chirps = 0;
  for (const SweepHold& h : plan.holds) {
    if (h.segment == SweepSegment::step) {
      ++steps;
      EXPECT_EQ(h.duration_s, 0.6);
      EXPECT_GE(h.level_kPa, 10.0);  // never to 0 (an exhausting regulator is not its lag)
      EXPECT_LE(h.level_kPa, 60.0);
    }
    if (h.segment == SweepSegment::chirp) {
      ++chirps;
      EXPECT_EQ(h.duration_s, 8.0);
      EXPECT_NEAR(h.command_at(0), h.level_kPa, 1e-12);  // starts at its centre
      double lo = 1e9, hi = -1e9;
      for (double t = 0; t <= 8; t += 0.001) lo = std::min(lo, h.command_at(t)), hi = std::max(hi, h.command_at(t));
      EXPECT_NEAR(hi - lo, 2 * 12.5, 0.05);  // a quarter of 10..60 either way
    }
  }
  EXPECT_EQ(steps, 11u);
  EXPECT_EQ(chirps, 1u);

  TempDir dir;
  PlantParams plant;
  const SweepData data = recorded_sweep(dir, plant, "dynamics");
  EXPECT_TRUE(data.points.size() >= 3u);  // the vent holds
  const auto ch1 = data.channel_dynamics(1);
  ASSERT_GT(ch1.size(), 14000u);  // 11 x 0.6 s + 8 s at 1 kHz
  for (std::size_t k = 1; k < 1000; ++k) ASSERT_NEAR(ch1[k].t_s - ch1[k - 1].t_s, 0.001, 1e-4) << k;
  // The command column holds what the safety stage let through: a 15 kPa step climbs at the
  // rig's 2000 kPa/s, 2 kPa per sample.
  double largest_step = 0;
  for (std::size_t k = 1; k < ch1.size(); ++k)
    largest_step = std::max(largest_step, std::abs(ch1[k].command_kPa - ch1[k - 1].command_kPa));
  EXPECT_LE(largest_step, 2.0 + 1e-3);
}

TEST(DynamicsFit, RecoversTheSimulatedPlantsDeadTimeAndLag) {
  TempDir dir;
  // A heavier plant than the default: more play, longer dead time and lag.
  PlantParams plant;
  plant.hysteresis_kPa = 3.4;
  plant.dead_time_s = 0.007;
  plant.time_constant_s = 0.070;
  const SweepData data = recorded_sweep(dir, plant);
  CalibrationFitOptions o;
  o.date = "2026-11-26";
  const CalibrationResult r = fit_calibration(data, o);
  for (const ChannelCalibration& ch : r.channels) {
    ASSERT_TRUE(ch.dynamics.has_value()) << ch.channel;
    const DynamicsFit& d = *ch.dynamics;
    // The simulated plant feels a command at the end of the step one dead time after it was
    // given, so at 1 kHz its dead time as a continuous model is one sample shorter.
    EXPECT_NEAR(d.dead_time_s, plant.dead_time_s - 0.001, 0.0005) << ch.channel;
    EXPECT_NEAR(d.time_constant_s, plant.time_constant_s, 0.03 * plant.time_constant_s) << ch.channel;
    EXPECT_GT(d.r_squared, 0.999);
    EXPECT_NEAR(d.rate_hz, 1000, 1e-6);
    EXPECT_NEAR(d.rms_residual_kPa, plant.noise_sd_kPa, 0.05);  // what is left is the monitor's noise
    ASSERT_EQ(d.segments.size(), 2u);
    EXPECT_EQ(d.segments[0].segment, SweepSegment::step);
    EXPECT_EQ(d.segments[1].segment, SweepSegment::chirp);
    EXPECT_TRUE(d.converged) << d.solver_report;
    EXPECT_TRUE(ch.dynamics_usable());
    EXPECT_FALSE(d.directional);  // one lag both ways: a second one would not pay
  }
  // Written to the calibration file and read back by the controller's loader.
  const auto path = dir.path() / "cal.json";
  const CalibrationModels cal = write_calibration_file(path, calibration_json(r));
  ASSERT_TRUE(cal.dynamics[0].has_value());
  EXPECT_EQ(cal.dynamics[0]->dead_time_s, r.channels[0].dynamics->dead_time_s);
  EXPECT_FALSE(cal.lag_compensation.enabled);  // off until switched on
  EXPECT_EQ(cal.lag_compensation.max_lead_kPa, 10.0);
}

TEST(DynamicsFit, APoorFitIsReportedAndKeepsLagCompensationOff) {
  TempDir dir;
  // A monitor so noisy that a first-order model explains too little of it.
  PlantParams plant;
  plant.noise_sd_kPa = 3.0;
  const SweepData data = recorded_sweep(dir, plant, "dynamics");
  CalibrationFitOptions o;
  o.date = "2026-11-26";
  o.hysteresis_from = HysteresisSource::none;
  o.lag_compensation.enabled = true;
  const CalibrationResult r = fit_calibration(data, o);
  ASSERT_TRUE(r.channels[0].dynamics.has_value());
  EXPECT_LT(r.channels[0].dynamics->r_squared, 0.98);
  EXPECT_FALSE(r.channels[0].dynamics_usable());
  bool said = false;
  for (const auto& n : r.notes) said = said || n.find("channel 1: its dynamics fit with R^2") != std::string::npos;
  EXPECT_TRUE(said);
  const CalibrationModels cal = write_calibration_file(dir.path() / "poor.json", calibration_json(r));
  EXPECT_TRUE(cal.lag_compensation.enabled);
  const TickConfig cfg =
      make_tick_config(load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated.json"), cal);
  for (std::size_t i = 0; i < kFingerCount; ++i) EXPECT_FALSE(cfg.lag_compensation.whole(i)) << i;
  const auto notes = describe_lag_compensation(cal);
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_NE(notes[0].find("lag compensation stays off on channel 1: its identified dynamics fit with R^2 0."),
            std::string::npos)
      << notes[0];
}

TEST(DynamicsFit, RefusesDataThatCannotIdentifyAnything) {
  std::vector<DynamicsSample> few(50);
  for (std::size_t k = 0; k < few.size(); ++k) few[k] = {1, 0, SweepSegment::step, k * 0.001, 20, 20, k + 10};
  EXPECT_EQ(refusal([&] { fit_dynamics(few, nullptr, {}, "DATA.csv", "channel 1 dynamics"); }),
            "DATA.csv: channel 1 dynamics: at least 200 evenly spaced step and chirp samples to identify the "
            "regulator's dynamics, got 49 (calibrate sweep --excitation ...,step,chirp)");
  std::vector<DynamicsSample> still(1000);
  for (std::size_t k = 0; k < still.size(); ++k) still[k] = {1, 0, SweepSegment::step, k * 0.001, 20, 20, k + 10};
  EXPECT_EQ(refusal([&] { fit_dynamics(still, nullptr, {}, "DATA.csv", "channel 1 dynamics"); }),
            "DATA.csv: channel 1 dynamics: step and chirp commands that move by at least 1 kPa");
  still[500].monitor_kPa = std::nan("");
  EXPECT_EQ(refusal([&] { fit_dynamics(still, nullptr, {}, "DATA.csv", "channel 1 dynamics"); }),
            "DATA.csv: line 510: a monitor reading for the dynamics fit of channel 1 dynamics");
}

TEST(CalibrationFile, DynamicsAndLagCompensationAreValidatedAndOlderFilesLoad) {
  TempDir dir;
  const std::string ch = R"({"actuator": {"slope": 0.25, "intercept_kPa": 5}})";
  auto with_dynamics = [](const std::string& d) {
    return R"({"actuator": {"slope": 0.25, "intercept_kPa": 5}, "dynamics": )" + d + "}";
  };
  auto load = [&](const std::string& channel3, const std::string& extra) {
    const auto p = dir.write("c.json", R"({"version": 1, "rig_id": "r", "channels": [)" + ch + "," + ch + "," +
                                           channel3 + "]" + extra + "}");
    return refusal([&] { load_calibration_file(p); });
  };
  const std::string f = (dir.path() / "c.json").string();
  const std::string good = R"({"dead_time_s": 0.004, "time_constant_s": 0.05, "r_squared": 0.999})";
  EXPECT_EQ(load(with_dynamics(good), R"(, "lag_compensation": {"enabled": true, "max_lead_kPa": 5})"), "accepted");
  EXPECT_EQ(load(with_dynamics(R"({"dead_time_s": 0.9, "time_constant_s": 0.05, "r_squared": 0.999})"), ""),
            f + ": channels[2].dynamics.dead_time_s: a number in 0..0.5, got 0.9");
  EXPECT_EQ(load(with_dynamics(R"({"dead_time_s": 0.004, "time_constant_s": 0, "r_squared": 0.999})"), ""),
            f + ": channels[2].dynamics.time_constant_s: a number in 0.0005..2, got 0");
  EXPECT_EQ(load(with_dynamics(R"({"dead_time_s": 0.004, "time_constant_s": 0.05})"), ""),
            f + ": channels[2].dynamics.r_squared: a value (field is missing)");
  EXPECT_EQ(load(with_dynamics(R"({"dead_time_s": 0.004, "time_constant_s": 0.05, "r_squared": 0.99, "lag": 1})"), ""),
            f + ": channels[2].dynamics.lag: no such field here (unknown field; check its spelling)");
  EXPECT_EQ(load(ch, R"(, "lag_compensation": {"enabled": true})"),
            f + ": lag_compensation.enabled: identified regulator dynamics (channels[].dynamics, from calibrate sweep "
                "--excitation ...,step,chirp and calibrate fit) before lag compensation is enabled");
  EXPECT_EQ(load(with_dynamics(good), R"(, "lag_compensation": {"min_r_squared": 0.5})"),
            f + ": lag_compensation.min_r_squared: a number in 0.9..1, got 0.5");
  EXPECT_EQ(load(with_dynamics(good), R"(, "lag_compensation": {"max_lead_kPa": -1})"),
            f + ": lag_compensation.max_lead_kPa: a number in 0..100, got -1");
  // Files written before dynamics existed load as before: no whole-target compensation.
  for (const char* shipped : {"paper002.json", "sim-default.json"}) {
    const CalibrationModels cal =
        load_calibration_file(std::string(PALPRIG_SOURCE_DIR) + "/data/calibration/" + shipped);
    EXPECT_FALSE(cal.lag_compensation.enabled) << shipped;
  }
  EXPECT_EQ(load(ch, ""), "accepted");
}

TEST(DynamicsFit, SeparateFillAndExhaustLagsAreIdentified) {
  // A regulator that fills through its supply in 40 ms and exhausts in 90 ms.
  TempDir dir;
  PlantParams plant;
  plant.time_constant_s = 0.040;
  plant.exhaust_time_constant_s = 0.090;
  const SweepData data = recorded_sweep(dir, plant);
  CalibrationFitOptions o;
  o.date = "2026-11-27";
  const CalibrationResult r = fit_calibration(data, o);
  for (const ChannelCalibration& ch : r.channels) {
    ASSERT_TRUE(ch.dynamics.has_value()) << ch.channel;
    const DynamicsFit& d = *ch.dynamics;
    ASSERT_TRUE(d.directional) << ch.channel;
    EXPECT_NEAR(d.time_constant_s, 0.040, 0.03 * 0.040) << ch.channel;
    EXPECT_NEAR(d.exhaust_time_constant_s, 0.090, 0.03 * 0.090) << ch.channel;
    EXPECT_NEAR(d.dead_time_s, plant.dead_time_s - 0.001, 0.0005) << ch.channel;
    EXPECT_GT(d.r_squared, 0.999);
    EXPECT_LT(d.rms_residual_kPa, 0.5 * d.one_lag_rms_residual_kPa);  // what one lag could not explain
  }
  // The file carries the exhaust lag; the tick's compensator gets both.
  const CalibrationModels cal = write_calibration_file(dir.path() / "cal.json", calibration_json(r));
  ASSERT_TRUE(cal.dynamics[1].has_value());
  EXPECT_EQ(cal.dynamics[1]->exhaust_time_constant_s, r.channels[1].dynamics->exhaust_time_constant_s);
  const TickConfig cfg =
      make_tick_config(load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated.json"), cal);
  EXPECT_EQ(cfg.lag_compensation.regulator[1].exhaust_time_constant_s, cal.dynamics[1]->exhaust_time_constant_s);
  EXPECT_EQ(cfg.lag_compensation.regulator[1].time_constant_s, cal.dynamics[1]->time_constant_s);
}
