// The tick's lag compensation stage: with the regulators' identified dynamics it commands the
// inverse of their lag toward the scene sampled where the fingers will be, so a step, a ramp and
// a tumor crossing at 40 mm/s arrive on time; its commands stay within [0, p_max], the slew
// limit and the lead bound (a wrong model pushes no harder than that); a channel whose model
// fits poorly keeps it off; it reads past pen samples only; the pulse uses the same mechanism.
// Just over 400 lines: one file for the one stage, each property above a case of its own.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "controller/lag_compensation_stage.hpp"
#include "controller/rig_step.hpp"
#include "controller/tick.hpp"
#include "controller/tick_setup.hpp"
#include "formats/rig_file.hpp"
#include "models/pneumatic_plant.hpp"
#include "models/tissue_scene.hpp"
#include "rigs/simulated_rig.hpp"
#include "tests/support/lag_stage_drive.hpp"

using namespace palprig;
using palprig::testing::drive_stage;
using palprig::testing::lag_only_plant;
using palprig::testing::StageDrive;

namespace {

const std::string kLagCompensationData = std::string(PALPRIG_SOURCE_DIR) + "/data/";

// What calibration identifies on that plant at 1 kHz (calibration/dynamics_fit.hpp: the plant
// feels a command at the end of the step one dead time after it, so 1 ms less dead time).
constexpr RegulatorLag kIdentified{0.004, 0.050, 2000};

// Every channel identified as `model`; the whole target compensated or not (the pulse, when
// there is one, always is).
void identify_every_channel(TickConfig& cfg, const RegulatorLag& model, bool whole_target) {
  cfg.lag_compensation.whole_target = whole_target;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    cfg.lag_compensation.identified[i] = true;
    cfg.lag_compensation.regulator[i] = model;
  }
}

double rms_error(const StageDrive& d, std::size_t from = 0, std::size_t to = SIZE_MAX) {
  double s = 0;
  std::size_t n = 0;
  for (std::size_t k = from; k < std::min(to, d.target.size()); ++k, ++n) s += std::pow(d.output[k] - d.target[k], 2);
  return std::sqrt(s / double(n));
}

// Ticks from the step: the first where the output reaches `fraction` of the final 10 kPa.
std::size_t time_to(const StageDrive& d, double level) {
  for (std::size_t k = 100; k < d.output.size(); ++k)
    if (d.output[k] >= level) return k - 100;
  return SIZE_MAX;
}

}  // namespace

TEST(LagCompensation, StepArrivesOnTimeWithoutOvershootWithinItsLimits) {
  auto step = [](double t) { return t >= 0.1 ? 10.0 : 0.0; };
  const StageDrive plain = drive_stage(step, false, kIdentified, 10, 0.6);
  const StageDrive comp = drive_stage(step, true, kIdentified, 10, 0.6);
  // Uncompensated: a dead time, then 50 ms to 63 %, over 100 ms to 90 %. Compensated, with the
  // command at most 10 kPa above the 10 kPa target (twice the target), the lag's 90 % comes in
  // tau ln(20 / 11), a third of the time.
  const std::size_t plain_90 = time_to(plain, 9.0), comp_90 = time_to(comp, 9.0);
  EXPECT_GT(plain_90, 110u);
  EXPECT_LT(comp_90, 40u) << "ms to 90 %";
  // Sampled one lead ahead, the rise starts at the step itself, not a dead time after it.
  EXPECT_LT(comp.output[100 + 1], 0.2);                        // not before the edge...
  EXPECT_GT(comp.output[100 + 6], 2 * plain.output[100 + 6]);  // ...but right after it
  double overshoot = 0, max_command = 0, max_step = 0;
  for (std::size_t k = 0; k < comp.output.size(); ++k) {
    overshoot = std::max(overshoot, comp.output[k] - 10.0);
    max_command = std::max(max_command, comp.command[k]);
    if (k > 0) max_step = std::max(max_step, std::abs(comp.command[k] - comp.command[k - 1]));
    EXPECT_GE(comp.command[k], 0.0);
  }
  EXPECT_LT(overshoot, 0.15);
  EXPECT_LE(max_command, 10.0 + 10.0 + 1e-9);  // the lead bound
  EXPECT_LE(max_step, 2.0 + 1e-9);             // the slew limit: 2000 kPa/s at 1 kHz
  EXPECT_LT(rms_error(comp), 0.75 * rms_error(plain));
}

TEST(LagCompensation, RampIsTrackedWithoutTheLagsOffset) {
  auto ramp = [](double t) { return std::clamp((t - 0.1) * 50.0, 0.0, 20.0); };  // 50 kPa/s to 20 kPa
  const StageDrive plain = drive_stage(ramp, false, kIdentified, 10, 0.8);
  const StageDrive comp = drive_stage(ramp, true, kIdentified, 10, 0.8);
  // Mid-ramp (0.3-0.45 s), the uncompensated output lags by rate x (dead time + lag) = 2.75 kPa.
  EXPECT_NEAR(rms_error(plain, 300, 450), 50 * 0.055, 0.3);
  EXPECT_LT(rms_error(comp, 300, 450), 0.1);
  EXPECT_LT(rms_error(comp), 0.2 * rms_error(plain));
}

TEST(LagCompensation, AWrongModelPushesNoHarderThanTheLeadBound) {
  auto step = [](double t) { return t >= 0.1 && t < 0.4 ? 10.0 : 2.0; };
  // The model says the regulator is four times slower and later than it is: it boosts too long.
  const RegulatorLag wrong{0.012, 0.200, 2000};
  for (double lead : {0.0, 3.0}) {
    const StageDrive d = drive_stage(step, true, wrong, lead, 0.7);
    double worst_command = 0, worst_output = 0;
    for (std::size_t k = 0; k < d.command.size(); ++k) {
      // Never more than the lead above what is asked now or one lead ahead...
      const double t = k * 0.001;
      const double asked = std::max(step(t), step(t + wrong.dead_time_s + 0.001));
      EXPECT_LE(d.command[k], asked + lead + 1e-9) << k;
      worst_command = std::max(worst_command, d.command[k] - 10.0);
      worst_output = std::max(worst_output, d.output[k] - 10.0);
    }
    // ...so the fingertip never gets more than the lead above the hardest target: with no lead,
    // never harder than the uncompensated rig (whose regulator tends to the target from below).
    EXPECT_LE(worst_command, lead + 1e-9);
    EXPECT_LE(worst_output, lead + 1e-9);
    if (lead == 0.0) {
      EXPECT_LE(worst_output, 1e-9);
    }
  }
}

namespace {

// A 120 x 120 mm silicone block with a hard disc tumor (radius 8 mm) at (60, 60), sharp-edged.
MapScene tumor_map() {
  const int n = 241;  // 0.5 mm apart
  std::vector<float> v(std::size_t(n) * n, 0.f);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      if (std::hypot(c * 0.5 - 60, r * 0.5 - 60) <= 8.0) v[std::size_t(r) * n + c] = 1.f;
  return MapScene(StiffnessMap(n, n, 120, 120, v), MapSampling::nearest);
}

struct Crossing {
  double rms_kPa = 0, tumor_ratio = 0, max_setpoint_kPa = 0, max_compensated_kPa = 0, max_output_kPa = 0;
  std::vector<double> setpoint;
};

// Finger 1 (at the pen) crosses the tumor at 40 mm/s, 2 N, on the simulated rig without play or
// noise, through RigStep (tick, backend, monitors).
// tracked: the same finger 1 as a tracked fingertip (its own position and load cell),
// finger 2 tracked elsewhere on soft tissue, finger 3's tool out of view (vented).
Crossing cross_tumor(bool compensate, const RegulatorLag& model, double max_lead_kPa = 10, double stop_at_s = 1e9,
                     bool tracked = false) {
  const MapScene scene = tumor_map();
  RigConfig rig;
  for (auto& p : rig.plants) p = lag_only_plant();
  CalibrationModels cal;
  TickConfig cfg = make_tick_config(rig, cal);
  identify_every_channel(cfg, model, compensate);
  cfg.lag_compensation.max_lead_kPa = max_lead_kPa;
  SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
  backend.open();
  RigStep step(cfg, backend);
  step.arm();
  Crossing c;
  double sq = 0, mon = 0, tgt = 0;
  std::size_t n = 0;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * 0.001;
    const double x = 30 + 40 * std::min(t, stop_at_s);  // from x = 30 to 110 mm
    TouchSample pen{t, x, 60, 2.0, true};
    if (tracked) {
      // A 60 Hz tracker read by the 1 kHz loop: each pose held until the next.
      const double t_pose = std::floor(t * 60.0) / 60.0;
      const double x_pose = 30 + 40 * std::min(t_pose, stop_at_s);
      pen = TouchSample{t_pose, x_pose, 60, 2.0, true};
      pen.own_positions = pen.per_finger_force = true;
      pen.fingers[0] = {x_pose, 60, -1, 2.0, FingerVent::none};
      pen.fingers[1] = {x_pose, 20, -1, 1.5, FingerVent::none};
      pen.fingers[2] = {0, 0, 0, 0, FingerVent::tool_stale};
    }
    const StepResult& r = step.step(scene, pen, t);
    if (tracked) {
      EXPECT_EQ(r.tick.setpoint_kPa[2], 0.0) << k;       // the vented finger gets nothing, compensated or not
      EXPECT_LT(r.tick.record.target_kPa[1], 1.0) << k;  // finger 2 stays on soft tissue
    }
    const double target = r.tick.record.target_kPa[0], out = r.monitor_kPa[0];
    c.setpoint.push_back(r.tick.setpoint_kPa[0]);
    c.max_setpoint_kPa = std::max(c.max_setpoint_kPa, r.tick.setpoint_kPa[0]);
    c.max_compensated_kPa = std::max(c.max_compensated_kPa, r.tick.compensated_kPa[0]);
    c.max_output_kPa = std::max(c.max_output_kPa, out);
    sq += (out - target) * (out - target);
    ++n;
    if (std::abs(r.tick.record.finger_x_mm[0] - 60) <= 8) mon += out, tgt += target;
  }
  c.rms_kPa = std::sqrt(sq / double(n));
  c.tumor_ratio = mon / tgt;
  return c;
}

}  // namespace

TEST(LagCompensation, TumorCrossingAt40mmPerSecondArrivesOnTime) {
  const Crossing plain = cross_tumor(false, kIdentified), comp = cross_tumor(true, kIdentified);
  // The tumor asks for 11.75 kPa for 0.4 s. Uncompensated the regulator reaches about three
  // quarters of it over the tumor on average and the edges come a lag late.
  EXPECT_LT(plain.tumor_ratio, 0.9);
  EXPECT_GT(comp.tumor_ratio, 0.95);
  EXPECT_LT(comp.rms_kPa, 0.5 * plain.rms_kPa);
  EXPECT_LE(comp.max_setpoint_kPa, 60.0);
  EXPECT_LE(comp.max_compensated_kPa, 11.75 + 10.0 + 1e-9);
  EXPECT_LT(comp.max_output_kPa, 11.75 + 0.2);
}

TEST(LagCompensation, TrackedFingersCrossATumorOnTimeFromTheirOwnPastPoses) {
  // The same crossing with the finger placed by a 60 Hz tracker and pressed by its own load cell:
  // the stage extrapolates that finger's own past poses (not a pen's triangle), a vented
  // finger is left at 0 kPa, and the edges still arrive on time.
  const Crossing plain = cross_tumor(false, kIdentified, 10, 1e9, true),
                 comp = cross_tumor(true, kIdentified, 10, 1e9, true);
  EXPECT_LT(plain.tumor_ratio, 0.9);
  EXPECT_GT(comp.tumor_ratio, 0.95);
  EXPECT_LT(comp.rms_kPa, 0.6 * plain.rms_kPa);
  EXPECT_LE(comp.max_setpoint_kPa, 60.0);
  EXPECT_LT(comp.max_output_kPa, 11.75 + 0.2);
}

TEST(LagCompensation, NeverAboveTheUncompensatedCommandBoundWithAWrongModelAndNoLead) {
  // A badly wrong model (3x the dead time, 4x the lag) with no lead allowed: every compensated
  // command stays at or below the hardest target the uncompensated rig commands (11.75 kPa), so
  // the fingertip never gets more than the uncompensated rig would give it.
  const Crossing plain = cross_tumor(false, kIdentified);
  const Crossing wrong = cross_tumor(true, RegulatorLag{0.012, 0.200, 2000}, 0.0);
  EXPECT_LE(wrong.max_compensated_kPa, plain.max_compensated_kPa + 1e-9);
  EXPECT_LE(wrong.max_output_kPa, plain.max_compensated_kPa + 1e-9);
}

TEST(LagCompensation, UsesPastPenSamplesOnly) {
  // Two pens that agree until 0.45 s (finger 1 4 mm short of the tumor's edge), then one stops
  // dead: every setpoint up to 0.45 s is the same, whatever the future held.
  const Crossing goes_on = cross_tumor(true, kIdentified), stops = cross_tumor(true, kIdentified, 10, 0.45);
  for (std::size_t k = 0; k <= 450; ++k) ASSERT_EQ(goes_on.setpoint[k], stops.setpoint[k]) << k;
  EXPECT_NE(goes_on.setpoint[700], stops.setpoint[700]);
}

TEST(LagCompensation, AChannelWhoseModelFitsPoorlyKeepsItOffAndSaysWhy) {
  const RigConfig rig = load_rig_file(kLagCompensationData + "rigs/simulated.json");
  CalibrationModels cal;
  cal.lag_compensation.enabled = true;
  cal.dynamics[0] = RegulatorDynamics{0.004, 0.05, 0.9991, 0.1, 0.4, 12000, 1000};
  cal.dynamics[1] = RegulatorDynamics{0.004, 0.05, 0.9500, 2.1, 9.0, 12000, 1000};  // below 0.98
  const TickConfig cfg = make_tick_config(rig, cal);
  EXPECT_TRUE(cfg.lag_compensation.whole(0));
  EXPECT_FALSE(cfg.lag_compensation.whole(1));
  EXPECT_FALSE(cfg.lag_compensation.whole(2));  // nothing identified
  const auto notes = describe_lag_compensation(cal);
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_NE(notes[0].find("lag compensation on for channel 1 (dead time 4.0 ms, lag 50.0 ms)"), std::string::npos)
      << notes[0];
  EXPECT_NE(notes[1].find("channel 2: its identified dynamics fit with R^2 0.9500, below the bound 0.9800"),
            std::string::npos)
      << notes[1];
  EXPECT_NE(notes[2].find("channel 3: no identified dynamics"), std::string::npos) << notes[2];
  // The refused channel runs exactly as the uncompensated rig; the accepted one does not.
  CalibrationModels off = cal;
  off.lag_compensation.enabled = false;
  const TickConfig plain = make_tick_config(rig, off);
  const MapScene scene = tumor_map();
  TickState a = make_tick_state(cfg), b = make_tick_state(plain);
  bool channel_1_differs = false;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * 0.001;
    const TouchSample pen{t, 30 + 40 * t, 60 - 16 * 0, 2.0, true};
    const TickResult ra = tick(a, cfg, scene, pen, t), rb = tick(b, plain, scene, pen, t);
    ASSERT_EQ(ra.setpoint_kPa[1], rb.setpoint_kPa[1]) << k;
    ASSERT_EQ(ra.setpoint_kPa[2], rb.setpoint_kPa[2]) << k;
    channel_1_differs = channel_1_differs || ra.setpoint_kPa[0] != rb.setpoint_kPa[0];
    EXPECT_EQ((ra.record.flags & kLagCompensated) != 0, true);
  }
  EXPECT_TRUE(channel_1_differs);
}

TEST(LagCompensation, ThePulseRidesOnTheSameMechanism) {
  // A brachial pulse with the whole target compensated: the compensator that now stands for the
  // stiffness and the pulse together still delivers the pulse on time.
  const RigConfig rig = load_rig_file(kLagCompensationData + "rigs/simulated.json");
  TissueDefinition t;
  t.body = {{80, 60}, 80, 60, 6};
  t.layers = {{"skin", 1.5, 40}, {"fat", 3.5, 4}, {"muscle", 50, 15}};
  t.felt = {4, 300};
  ArterySpec a;
  a.name = "test";
  a.path = {{0, 60}, {160, 60}};
  a.depth_mm = 5;
  a.radius_mm = 2.5;
  a.amplitude_kPa = 8;
  a.rate_bpm = 80;
  a.force_window = {0.5, 3.0, 1.0};
  const FunctionScene scene(t, std::vector<ArterySpec>{a});
  auto correlation = [&](bool whole) {
    RigConfig r = rig;
    for (auto& p : r.plants) p = lag_only_plant();
    TickConfig cfg = make_tick_config(r, CalibrationModels{});
    identify_every_channel(cfg, kIdentified, whole);
    SimulatedRig backend(r.plants, r.safety.p_max_kPa);
    backend.open();
    RigStep step(cfg, backend);
    step.arm();
    std::vector<double> want, got;
    for (int k = 0; k < 8000; ++k) {
      const double time = k * 0.001;
      const StepResult& s = step.step(scene, {time, 40, 60, 2.5, true}, time);
      if (k >= 2000) {
        want.push_back(s.tick.record.target_kPa[0]);
        got.push_back(s.monitor_kPa[0]);
      }
    }
    double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
    for (std::size_t i = 0; i < want.size(); ++i) ma += want[i], mb += got[i];
    ma /= double(want.size());
    mb /= double(got.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
      sab += (want[i] - ma) * (got[i] - mb);
      saa += (want[i] - ma) * (want[i] - ma);
      sbb += (got[i] - mb) * (got[i] - mb);
    }
    return sab / std::sqrt(saa * sbb);
  };
  const double pulse_only = correlation(false), whole = correlation(true);
  EXPECT_GT(pulse_only, 0.95);
  EXPECT_GT(whole, 0.95);
}

TEST(LagCompensation, ARestartFromVentedStartsTheCompensatorsFromZero) {
  TickConfig cfg;
  identify_every_channel(cfg, kIdentified, true);
  const MapScene scene = tumor_map();
  TickState st = make_tick_state(cfg);
  for (int k = 0; k < 300; ++k) tick(st, cfg, scene, {k * 0.001, 60, 60, 2.0, true}, k * 0.001);
  EXPECT_GT(st.lag.compensator[0].predicted_kPa(), 10.0);
  st.restart_from_vented();
  EXPECT_EQ(st.lag.compensator[0].predicted_kPa(), 0.0);
  EXPECT_EQ(st.lag.compensator[0].last_command_kPa(), 0.0);
}

TEST(LagCompensation, FillAndExhaustLagsEachLeadTheirOwnEdges) {
  // A regulator that fills in 40 ms and exhausts in 90 ms, stepping 10 -> 20 -> 12 kPa: the
  // compensator with both lags lands both edges without overshoot; with one lag (either) it
  // overshoots the edge whose lag it overestimates or arrives late on the one it underestimates.
  PlantParams plant = lag_only_plant();
  plant.time_constant_s = 0.040;
  plant.exhaust_time_constant_s = 0.090;
  auto steps = [](double t) { return t < 0.1 ? 10.0 : t < 0.5 ? 20.0 : 12.0; };
  const RegulatorLag both{0.004, 0.040, 2000, 0.090}, fill_only{0.004, 0.040, 2000}, exhaust_only{0.004, 0.090, 2000};
  const StageDrive d = drive_stage(steps, true, both, 10, 1.0, plant);
  const StageDrive f = drive_stage(steps, true, fill_only, 10, 1.0, plant);
  const StageDrive e = drive_stage(steps, true, exhaust_only, 10, 1.0, plant);
  double over_rise = 0, under_fall = 0;
  for (std::size_t k = 100; k < 500; ++k) over_rise = std::max(over_rise, d.output[k] - 20.0);
  for (std::size_t k = 500; k < d.output.size(); ++k) under_fall = std::max(under_fall, 12.0 - d.output[k]);
  EXPECT_LT(over_rise, 0.15);
  EXPECT_LT(under_fall, 0.15);
  // Rising with the exhaust's slower lag assumed: pushed too hard, overshoots.
  double over_e = 0;
  for (std::size_t k = 100; k < 500; ++k) over_e = std::max(over_e, e.output[k] - 20.0);
  EXPECT_GT(over_e, 3 * std::max(over_rise, 0.05));
  // Falling with the fill's faster lag assumed: released too early, late.
  // Falling with the fill's faster lag assumed: released too early, it drags on for long after.
  // With both lags the fall lands 55 ms after the edge (dead time, then the command at 0 kPa).
  EXPECT_LT(std::abs(d.output[560] - 12.0), 0.1);
  EXPECT_GT(f.output[560] - 12.0, 1.0);
  EXPECT_LT(rms_error(d), std::min(rms_error(f), rms_error(e)));
}
