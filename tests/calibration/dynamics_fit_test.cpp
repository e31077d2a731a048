// The regulators' dynamics from the sweep's step and chirp rows: the sweep records them at the
// loop's rate with the setpoint actually sent, the fit recovers a simulated plant's dead time and
// lag (with its play through the hysteresis model), reports R^2 and residuals per excitation, a
// poorly fitting channel is marked and keeps lag compensation off, and the calibration file
// carries the dynamics and the lag_compensation section (and refuses them when impossible); an
// exhaust lag growing near 0 kPa is recovered from a synthetic sweep and kept by held-out error;
// a badly fitting channel of an asymmetric regulator keeps compensation off and says why.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>

#include "calibration/calibration_fit.hpp"
#include "calibration/calibration_report.hpp"
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
SweepData recorded_sweep_of(const TempDir& dir, const std::array<PlantParams, kFingerCount>& plants,
                            const std::string& excitation = "all") {
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

SweepData recorded_sweep(const TempDir& dir, const PlantParams& plant, const std::string& excitation = "all") {
  return recorded_sweep_of(dir, {plant, plant, plant}, excitation);
}

}  // namespace

TEST(DynamicsSweep, StepAndChirpAreRecordedAtTheLoopsRateWithTheSetpointSent) {
  const SweepSchedule plan = [] {
    SweepPlanOptions o;
    o.staircase = false;
    o.step = o.chirp = true;
    return plan_calibration_sweep(o, 60);
  }();
  std::size_t steps = 0, chirps = 0, to_zero = 0;
  double previous_kPa = 0;
  for (const SweepHold& h : plan.holds) {
    if (h.segment == SweepSegment::step) {
      ++steps;
      EXPECT_EQ(h.duration_s, 0.6);
      if (h.level_kPa == 0) {
        // A fall to 0 kPa, where the regulator exhausts, from a level of the range (the exhaust
        // near 0 kPa is what stage 4 identifies).
        ++to_zero;
        EXPECT_GE(previous_kPa, 10.0);
      } else {
        EXPECT_GE(h.level_kPa, 10.0);
        EXPECT_LE(h.level_kPa, 60.0);
      }
    }
    previous_kPa = h.level_kPa;
    if (h.segment == SweepSegment::chirp) {
      ++chirps;
      EXPECT_EQ(h.duration_s, 8.0);
      EXPECT_NEAR(h.command_at(0), h.level_kPa, 1e-12);  // starts at its centre
      double lo = 1e9, hi = -1e9;
      for (double t = 0; t <= 8; t += 0.001) lo = std::min(lo, h.command_at(t)), hi = std::max(hi, h.command_at(t));
      EXPECT_NEAR(hi - lo, 2 * 12.5, 0.05);  // a quarter of 10..60 either way
    }
  }
  EXPECT_EQ(steps, 14u);
  EXPECT_EQ(to_zero, 3u);
  EXPECT_EQ(chirps, 1u);

  TempDir dir;
  PlantParams plant;
  const SweepData data = recorded_sweep(dir, plant, "dynamics");
  EXPECT_TRUE(data.points.size() >= 3u);  // the vent holds
  const auto ch1 = data.channel_dynamics(1);
  ASSERT_GT(ch1.size(), 16000u);  // 14 x 0.6 s + 8 s at 1 kHz
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

TEST(DynamicsFit, AnExhaustLagGrowingNear0IsIdentifiedAndKeptByHeldOutError) {
  // The shipped asymmetric regulator's dynamics: 40 ms filling, 70 ms exhausting far from 0 kPa,
  // 2.5 times slower at 0 kPa (scale 5 kPa). The sweep's steps fall to 0 kPa three times, so the
  // slowdown below its lowest level (10 kPa, where it is only 1.5 times) is seen, not extrapolated.
  TempDir dir;
  PlantParams plant;
  plant.time_constant_s = 0.040;
  plant.exhaust_time_constant_s = 0.070;
  plant.exhaust_lag_factor_at_0 = 2.5;
  plant.exhaust_lag_scale_kPa = 5;
  const SweepData data = recorded_sweep(dir, plant);
  CalibrationFitOptions o;
  o.date = "2026-11-27";
  const CalibrationResult r = fit_calibration(data, o);
  const RegulatorLag truth{0.004, 0.040, 2000, 0.070, 2.5, 5};
  for (const ChannelCalibration& ch : r.channels) {
    ASSERT_TRUE(ch.dynamics.has_value()) << ch.channel;
    const DynamicsFit& d = *ch.dynamics;
    ASSERT_TRUE(d.directional) << ch.channel;
    ASSERT_TRUE(d.pressure_dependent) << ch.channel;
    EXPECT_TRUE(d.exhaust_lag_tried);
    EXPECT_LT(d.pressure_held_out_rms_kPa, 0.95 * d.directional_held_out_rms_kPa);
    EXPECT_NEAR(d.time_constant_s, 0.040, 0.03 * 0.040) << ch.channel;
    EXPECT_NEAR(d.dead_time_s, plant.dead_time_s - 0.001, 0.0005) << ch.channel;
    // The exhaust lag is the plant's at every pressure, down to the last kilopascal (before the
    // steps fell to 0 kPa, the fit put 102 ms at 0 kPa where the plant has 175).
    const RegulatorLag fitted{
        d.dead_time_s,          d.time_constant_s, 2000, d.exhaust_time_constant_s, d.exhaust_lag_factor_at_0,
        d.exhaust_lag_scale_kPa};
    for (double kPa : {0.0, 0.7, 2.0, 5.0, 10.0, 30.0, 60.0})
      EXPECT_NEAR(fitted.exhaust_tau_at(kPa), truth.exhaust_tau_at(kPa), 0.05 * truth.exhaust_tau_at(kPa))
          << ch.channel << " at " << kPa << " kPa";
    EXPECT_NEAR(d.exhaust_lag_factor_at_0, 2.5, 0.15) << ch.channel;
    EXPECT_NEAR(d.exhaust_lag_scale_kPa, 5.0, 1.0) << ch.channel;
    EXPECT_NEAR(d.rms_residual_kPa, plant.noise_sd_kPa, 0.03);  // what is left is the monitor's noise
  }
  // The file carries both keys; the tick's compensator gets them; a file with them but without
  // the exhaust lag they scale is refused.
  const CalibrationModels cal = write_calibration_file(dir.path() / "cal.json", calibration_json(r));
  ASSERT_TRUE(cal.dynamics[2].has_value());
  EXPECT_EQ(cal.dynamics[2]->exhaust_lag_factor_at_0, r.channels[2].dynamics->exhaust_lag_factor_at_0);
  EXPECT_EQ(cal.dynamics[2]->exhaust_lag_scale_kPa, r.channels[2].dynamics->exhaust_lag_scale_kPa);
  const TickConfig cfg =
      make_tick_config(load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated_asymmetric.json"), cal);
  EXPECT_EQ(cfg.lag_compensation.regulator[2].exhaust_lag_factor_at_0, cal.dynamics[2]->exhaust_lag_factor_at_0);
  EXPECT_EQ(cfg.lag_compensation.regulator[2].exhaust_lag_scale_kPa, cal.dynamics[2]->exhaust_lag_scale_kPa);
  const std::string ch = R"({"actuator": {"slope": 0.25, "intercept_kPa": 5}})";
  const auto bad = dir.write("bad.json", R"({"version": 1, "rig_id": "r", "channels": [)" + ch + "," + ch + "," +
                                             R"({"actuator": {"slope": 0.25, "intercept_kPa": 5}, "dynamics": )" +
                                             R"({"dead_time_s": 0.004, "time_constant_s": 0.05, "r_squared": 0.999, )" +
                                             R"("exhaust_lag_factor_at_0": 2, "exhaust_lag_scale_kPa": 5}}]})");
  EXPECT_EQ(refusal([&] { load_calibration_file(bad); }),
            (dir.path() / "bad.json").string() +
                ": channels[2].dynamics.exhaust_lag_factor_at_0: exhaust_time_constant_s beside it (the exhaust lag "
                "it scales)");
}

TEST(DynamicsFit, ABadlyFittingAsymmetricChannelKeepsCompensationOffAndSaysWhy) {
  // Two channels of the shipped asymmetric regulator's dynamics (fill and exhaust lags, an exhaust
  // slowing near 0 kPa, a saturating gain; its play left out) and a third whose regulator slews at only
  // 40 kPa/s: its steps are ramps, which no lag with dead time (one lag, two, or one growing near
  // 0 kPa) describes. Compensation is asked for; that channel keeps it off and the fit, the file's
  // loader and the run each say why, while the other two are compensated.
  TempDir dir;
  const RigConfig rig = load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated_asymmetric.json");
  std::array<PlantParams, kFingerCount> plants = rig.plants;
  for (PlantParams& p : plants) p.hysteresis_rising_kPa = p.hysteresis_falling_kPa = 0.0;  // the dynamics alone
  plants[2].slew_kPa_per_s = 40;
  const SweepData data = recorded_sweep_of(dir, plants, "dynamics");
  CalibrationFitOptions o;
  o.date = "2026-11-27";
  o.hysteresis_from = HysteresisSource::none;
  o.lag_compensation.enabled = true;
  const CalibrationResult r = fit_calibration(data, o);
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_TRUE(r.channels[i].dynamics.has_value());
    EXPECT_TRUE(r.channels[i].dynamics->directional) << i;
    EXPECT_TRUE(r.channels[i].dynamics_usable()) << i;
  }
  ASSERT_TRUE(r.channels[2].dynamics.has_value());
  EXPECT_LT(r.channels[2].dynamics->r_squared, 0.98);
  EXPECT_FALSE(r.channels[2].dynamics_usable());
  bool said = false;
  for (const auto& n : r.notes) said = said || n.find("channel 3: its dynamics fit with R^2") != std::string::npos;
  EXPECT_TRUE(said);
  std::ostringstream report;
  print_fit_report(report, r, "asym.json");
  EXPECT_NE(report.str().find("POOR FIT: compensation stays off"), std::string::npos) << report.str();
  const CalibrationModels cal = write_calibration_file(dir.path() / "asym.json", calibration_json(r));
  const TickConfig cfg = make_tick_config(rig, cal);
  EXPECT_TRUE(cfg.lag_compensation.whole(0));
  EXPECT_TRUE(cfg.lag_compensation.whole(1));
  EXPECT_FALSE(cfg.lag_compensation.whole(2));
  const auto notes = describe_lag_compensation(cal);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("lag compensation on for channels 1"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("ms exhausting"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("lag compensation stays off on channel 3: its identified dynamics fit with R^2 0."),
            std::string::npos)
      << notes[1];
}
