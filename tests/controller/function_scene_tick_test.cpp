// The tick's pulse stage on function scenes: fingers over an artery pulse at its rate, the
// force window and lifting the pen stop it, map scenes are untouched, the pulse keeps exact
// time over long runs at any loop rate, rate changes while running, lag compensation improves
// the waveform on the simulated rig, and no setpoint ever exceeds p_max.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "controller/operator_switches.hpp"
#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "controller/tick.hpp"
#include "models/tissue_scene.hpp"

using namespace palprig;

namespace {

const std::string kData = std::string(PALPRIG_SOURCE_DIR) + "/data/";

TickConfig rig_config() { return make_tick_config(load_rig_file(kData + "rigs/simulated.json"), CalibrationModels{}); }

// Soft tissue with an artery along y = 60 (so fingers 0 and 1 of the default layout, which lie
// along x, can both be over it), 5 mm deep, inside a firm vessel wall.
std::unique_ptr<FunctionScene> artery_scene(double bpm, PulseWaveform wave = PulseWaveform::rectangular(0.2),
                                            double amplitude_kPa = 8) {
  TissueDefinition t;
  t.body = {{80, 60}, 80, 60, 6};
  t.layers = {{"skin", 1.5, 40}, {"fat", 3.5, 4}, {"muscle", 50, 15}};
  t.felt = {4, 300};
  Inclusion wall;
  wall.name = "vessel";
  wall.kind = InclusionKind::other;
  wall.shape.tube({0, 60, 5}, {160, 60, 5}, 2.5);
  wall.stiffness_kPa = 30;
  t.inclusions.push_back(wall);
  ArterySpec a;
  a.name = "test";
  a.path = {{0, 60}, {160, 60}};
  a.depth_mm = 5;
  a.radius_mm = 2.5;
  a.amplitude_kPa = amplitude_kPa;
  a.rate_bpm = bpm;
  a.waveform = wave;
  a.force_window = {0.5, 3.0, 1.0};
  return std::make_unique<FunctionScene>(t, std::vector<ArterySpec>{a});
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= double(a.size());
  mb /= double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

}  // namespace

TEST(FunctionSceneTick, FingersOverTheArteryPulseAtItsRateOthersDoNot) {
  const auto scene = artery_scene(60);
  const TickConfig cfg = rig_config();
  TickState st = make_tick_state(cfg);
  std::array<int, 3> onsets{};
  std::array<double, 3> previous{}, lo{1e9, 1e9, 1e9}, hi{};
  for (int k = 0; k < 10000; ++k) {
    const double t = k * 0.001;
    const TickResult r = tick(st, cfg, *scene, {t, 40, 60, 2.5, true}, t);
    for (int i = 0; i < 3; ++i) {
      if (r.pulse_kPa[i] > 0.5 && previous[i] <= 0.5) ++onsets[i];
      previous[i] = r.pulse_kPa[i];
      if (k > 2000) {
        lo[i] = std::min(lo[i], r.setpoint_kPa[i]);
        hi[i] = std::max(hi[i], r.setpoint_kPa[i]);
      }
    }
  }
  EXPECT_EQ(onsets[0], 10);                 // 10 s at 60 BPM
  EXPECT_EQ(onsets[1], 10);                 // the second finger along the artery feels it too
  EXPECT_EQ(onsets[2], 0);                  // the third is 16 mm across it
  EXPECT_GT(hi[0] - lo[0], 8 * 0.8 * 0.8);  // amplitude 8 kPa * force factor (2.5-0.5)/2.5
  EXPECT_LT(hi[2] - lo[2], 0.5);
}

TEST(FunctionSceneTick, ForceOutsideTheWindowAndLiftingThePenStopThePulse) {
  const auto scene = artery_scene(90);
  const TickConfig cfg = rig_config();
  for (double force : {0.3, 3.5}) {
    TickState st = make_tick_state(cfg);
    double most = 0;
    for (int k = 0; k < 2000; ++k) {
      const double t = k * 0.001;
      most = std::max(most, tick(st, cfg, *scene, {t, 40, 60, force, true}, t).pulse_kPa[0]);
    }
    EXPECT_EQ(most, 0.0) << force;
  }
  TickState st = make_tick_state(cfg);
  for (int k = 0; k < 1000; ++k) tick(st, cfg, *scene, {k * 0.001, 40, 60, 2.0, true}, k * 0.001);
  EXPECT_TRUE(st.pulse.activation[0].on[0]);
  double lifted_max = 0;
  for (int k = 1000; k < 3000; ++k) {
    const TickResult r = tick(st, cfg, *scene, {k * 0.001, 40, 60, 0.0, false}, k * 0.001);
    lifted_max = std::max(lifted_max, r.pulse_kPa[0]);
    if (k > 1100) {
      EXPECT_EQ(r.setpoint_kPa[0], 0.0);  // down to 0 under the slew limit, and stays there
    }
  }
  EXPECT_EQ(lifted_max, 0.0);
  EXPECT_FALSE(st.pulse.activation[0].on[0]);
}

TEST(FunctionSceneTick, MapScenesAreUntouchedByThePulseStage) {
  const SceneFile map = load_scene_file(kData + "scenes/phantom_abc.json");
  ASSERT_EQ(map.scene->pulse(), nullptr);
  TickConfig with = rig_config(), without = rig_config();
  without.pulse.compensate_lag = false;
  for (auto& l : without.pulse.lag) l = {0, 0, 1};
  TickState a = make_tick_state(with), b = make_tick_state(without);
  for (int k = 0; k < 5000; ++k) {
    const double t = k * 0.001;
    const TouchSample s{t, 20 + 0.02 * k, 40 + 0.005 * k, 2.0, k % 1500 < 1200};
    const TickResult ra = tick(a, with, *map.scene, s, t), rb = tick(b, without, *map.scene, s, t);
    ASSERT_EQ(ra.setpoint_kPa, rb.setpoint_kPa) << k;
    ASSERT_EQ(ra.pulse_kPa, (ChannelPressures{}));
  }
  EXPECT_FALSE(a.pulse.clocks.started);  // the stage never ran
}

TEST(FunctionSceneTick, PulseKeepsExactTimeOverLongRunsAtAnyLoopRate) {
  // 5 minutes at 250 Hz and 30 s at 1 kHz, each tick up to a quarter period early or late: the
  // beats follow the timestamps.
  for (const auto& [rate_hz, seconds] : {std::pair{250.0, 300.0}, std::pair{1000.0, 30.0}}) {
    const auto scene = artery_scene(72);
    const TickConfig cfg = rig_config();
    TickState st = make_tick_state(cfg);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> jitter(-0.25, 0.25);
    const double period = 1.0 / rate_hz;
    int onsets = 0;
    double previous = 0, worst = 0;
    for (long k = 0;; ++k) {
      const double t = (static_cast<double>(k) + (k > 0 ? jitter(rng) : 0.0)) * period;
      if (t > seconds + 0.1) break;  // the last beat falls on t = seconds exactly
      const double p = tick(st, cfg, *scene, {t, 40, 60, 2.0, true}, t).pulse_kPa[0];
      if (p > 0.5 && previous <= 0.5 && k > 0) {
        ++onsets;
        worst = std::max(worst, std::abs(t - onsets * 60.0 / 72.0));
      }
      previous = p;
    }
    EXPECT_EQ(onsets, static_cast<int>(seconds * 72 / 60)) << rate_hz;
    EXPECT_LT(worst, 1.5 * period) << rate_hz;  // seen at the first tick after each onset
  }
}

TEST(FunctionSceneTick, RateChangedWhileRunningTakesEffectWithoutAJump) {
  const auto scene = artery_scene(60);
  const TickConfig cfg = rig_config();
  TickState st = make_tick_state(cfg);
  std::vector<double> onsets;
  double previous = 0;
  // The operator's switches as the loop reads them each tick; the window sets the rate at 4.1 s.
  OperatorSwitches switches;
  for (int k = 0; k < 8000; ++k) {
    const double t = k * 0.001;
    if (k == 4100) {
      EXPECT_TRUE(switches.request_pulse_rate_bpm(0, 120));
    }
    const double p = tick(st, cfg, *scene, {t, 40, 60, 2.0, true}, t, switches.read()).pulse_kPa[0];
    if (p > 0.5 && previous <= 0.5) onsets.push_back(t);
    previous = p;
  }
  // Beats at 0, 1, 2, 3, 4 s; the change at 4.1 s keeps the phase (0.1 of a beat), so the next
  // beat comes 0.45 s later at 120 BPM, then every 0.5 s.
  ASSERT_GE(onsets.size(), 10u);
  EXPECT_NEAR(onsets[4], 4.0, 0.0015);
  EXPECT_NEAR(onsets[5], 4.55, 0.0015);
  EXPECT_NEAR(onsets[6], 5.05, 0.0015);
  EXPECT_NEAR(onsets[9], 6.55, 0.0015);
}

TEST(FunctionSceneTick, LagCompensationImprovesTheWaveformOnTheSimulatedRig) {
  const RigConfig rig = load_rig_file(kData + "rigs/simulated.json");  // its plant: 5 ms + 50 ms lag, 2 kPa play
  auto correlation = [&](bool compensate, double bpm) {
    const auto scene = artery_scene(bpm);
    TickConfig cfg = make_tick_config(rig, CalibrationModels{});
    cfg.pulse.compensate_lag = compensate;
    TickState st = make_tick_state(cfg);
    SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
    backend.open();
    backend.arm();
    std::vector<double> want, got;
    ChannelPressures monitor{};
    for (int k = 0; k < 12000; ++k) {
      const double t = k * 0.001;
      const TickResult r = tick(st, cfg, *scene, {t, 40, 60, 2.5, true}, t);
      EXPECT_EQ(backend.write(r.setpoint_kPa, t), BackendStatus::ok);
      EXPECT_EQ(backend.read_monitors(monitor, t), BackendStatus::ok);
      if (k >= 2000) {
        want.push_back(r.pulse_kPa[0]);
        got.push_back(monitor[0]);
      }
    }
    return pearson(want, got);
  };
  for (double bpm : {60.0, 100.0}) {
    const double raw = correlation(false, bpm), comp = correlation(true, bpm);
    EXPECT_GT(comp, 0.9) << bpm;
    EXPECT_GT(comp, raw + 0.15) << bpm;
  }
}

TEST(FunctionSceneTick, NoSetpointAbovePmaxEvenWhileBoosting) {
  const auto scene = artery_scene(160, PulseWaveform::rectangular(0.2), 80);  // a pulse beyond p_max
  TickConfig cfg = rig_config();
  TickState st = make_tick_state(cfg);
  bool clamped = false;
  for (int k = 0; k < 5000; ++k) {
    const double t = k * 0.001;
    const TickResult r = tick(st, cfg, *scene, {t, 40, 60, 3.0, true}, t);
    for (double p : r.setpoint_kPa) {
      ASSERT_TRUE(std::isfinite(p));
      ASSERT_GE(p, 0.0);
      ASSERT_LE(p, cfg.safety.p_max_kPa);
    }
    clamped |= (r.record.flags & kClamped) != 0 || r.setpoint_kPa[0] == cfg.safety.p_max_kPa;
  }
  EXPECT_TRUE(clamped);
  EXPECT_EQ(st.fault, FaultCode::none);
}

TEST(FunctionSceneTick, BreathingChangesWhatAFixedFingerFeels) {
  const SceneFile liver = load_scene_file(kData + "scenes/liver_edge.json");
  const TickConfig cfg = rig_config();
  TickState st = make_tick_state(cfg);
  // Below the costal margin, just past the liver's edge at rest: the edge arrives on inspiration.
  float rest = 0, inspired = 0;
  for (int k = 0; k <= 2000; ++k) {
    const double t = k * 0.001;
    const TickResult r = tick(st, cfg, *liver.scene, {t, 24, 80, 2.0, true}, t);
    if (k == 0) rest = r.record.stiffness[0];
    if (k == 2000) inspired = r.record.stiffness[0];
  }
  EXPECT_GT(inspired, rest + 0.1f);
}

TEST(FunctionSceneTick, AnArteryWithoutItsOwnForceWindowUsesTheCalibratedOne) {
  auto peak_at = [](const TickConfig& cfg, const Scene& scene, double force) {
    TickState st = make_tick_state(cfg);
    double most = 0;
    for (int k = 0; k < 1500; ++k) {
      const double t = k * 0.001;
      most = std::max(most, tick(st, cfg, scene, {t, 40, 60, force, true}, t).pulse_kPa[0]);
    }
    return most;
  };
  const auto shipped = artery_scene(80);
  ArterySpec a = shipped->arteries().artery(0).spec();
  a.own_force_window = false;  // as loaded from a scene that leaves "force_window_N" out
  a.force_window = ForceWindow{};
  const FunctionScene scene(shipped->field().definition(), {a});
  CalibrationModels cal;
  cal.force_window = MeasuredForceWindow{2.0, 4.0, 60, 120};
  const TickConfig calibrated = make_tick_config(load_rig_file(kData + "rigs/simulated.json"), cal);
  ASSERT_TRUE(calibrated.pulse.has_measured_window);
  EXPECT_EQ(peak_at(calibrated, scene, 1.8), 0.0);  // below the measured F_min (the default window would pulse)
  EXPECT_GT(peak_at(rig_config(), scene, 1.8), 0.0);
  EXPECT_GT(peak_at(calibrated, scene, 3.5), 0.0);
  EXPECT_GT(peak_at(calibrated, *shipped, 1.8), 0.0);  // an artery's own window wins
}

TEST(FunctionSceneTick, ATumorUnderASlidingFingerMovesWithItUntilTheSkinSlips) {
  // Skin that drags (sticks from 1 N, slips past 10 mm, relaxes in 20 ms) over a hard tumor
  // 4 mm deep at (40, 60): finger 1 presses on it and slides away along x at 40 mm/s.
  TissueDefinition t;
  t.body = {{80, 60}, 80, 60, 6};
  TissueLayer skin{"skin", 1.5, 40};
  skin.drag = DragSetting{1.0, 10.0, 0.02};
  skin.drag_given = true;
  t.layers = {skin, {"fat", 3.5, 4}, {"muscle", 50, 15}};
  t.felt = {4, 300};
  Inclusion tumor;
  tumor.name = "T";
  tumor.shape.sphere({40, 60, 6}, 5);
  tumor.stiffness_kPa = 300;
  t.inclusions.push_back(tumor);
  const FunctionScene scene(t, {});
  const TickConfig cfg = rig_config();
  auto slide = [&](double force_N, double release_at_mm) {
    TickState st = make_tick_state(cfg);
    std::vector<TickResult> out;
    for (int k = 0; k <= 500; ++k) {
      const double t_s = k * 0.001, x = 40 + 40 * t_s;  // 0 to 20 mm in 0.5 s
      const double f = x - 40 > release_at_mm ? 0.5 : force_N;
      out.push_back(tick(st, cfg, scene, {t_s, x, 60, f, true}, t_s));
    }
    return out;
  };
  TickState first = make_tick_state(cfg);
  const double on_tumor = tick(first, cfg, scene, {0, 40, 60, 2.0, true}, 0).record.stiffness[0];
  ASSERT_GT(on_tumor, 0.3);
  // Sticking (2 N): 8 mm on, the finger still feels the tumor it carries; the record says how far.
  const auto dragged = slide(2.0, 1e9);
  EXPECT_NEAR(dragged[200].record.stiffness[0], on_tumor, 1e-6);
  EXPECT_NEAR(dragged[200].record.drag_x_mm[0], 8.0, 1e-3);
  // Past 10 mm the skin slips: the tumor relaxes back and the finger, 12 mm on, feels soft tissue.
  EXPECT_LT(dragged[300].record.stiffness[0], 0.5 * on_tumor);
  EXPECT_LT(dragged[300].record.drag_x_mm[0], 10.0);
  // Pressing below f_stick (0.5 N from the start): no drag; the finger leaves the tumor behind.
  const auto light = slide(0.5, -1);
  EXPECT_EQ(light[200].record.drag_x_mm[0], 0.0f);
  // Released below f_stick after 4 mm: the carried tissue relaxes back (20 ms), nothing carried after.
  const auto released = slide(2.0, 4.0);
  EXPECT_NEAR(released[90].record.drag_x_mm[0], 3.6, 1e-3);
  EXPECT_LT(released[300].record.drag_x_mm[0], 1e-3);
  // Without a drag the tick is as before: finger 1 at 8 mm from the tumor's centre feels less.
  TissueDefinition plain = t;
  plain.layers[0].drag_given = false;
  const FunctionScene still_skin(plain, {});
  TickState st = make_tick_state(cfg);
  TickResult r;
  for (int k = 0; k <= 200; ++k) r = tick(st, cfg, still_skin, {k * 0.001, 40 + 0.04 * k, 60, 2.0, true}, k * 0.001);
  EXPECT_LT(r.record.stiffness[0], dragged[200].record.stiffness[0]);
  EXPECT_EQ(r.record.drag_x_mm[0], 0.0f);
}
