// Over 400 lines: the tick, the rig step and the end-to-end runs share one set of tracked-finger
// fixtures (a tracking file, a loopback OpenIGTLink server).
// Tracked fingers in the tick and the rig step, and end to end against a real
// OpenIGTLink server on loopback: fingers each at their own tracked position, per-finger load
// cells, a finger whose tool is out of view vented with its reason, the fingers following a
// known path within the registration error, pressure over a tumor, the pulse over an artery,
// and a tracker process killed for real venting everything.
#include <gtest/gtest.h>

#include <cstdio>

#include <signal.h>

#include <chrono>
#include <cmath>
#include <random>
#include <regex>
#include <thread>

#include "controller/loop_runner.hpp"
#include "controller/rig_step.hpp"
#include "controller/tick.hpp"
#include "controller/tick_setup.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "inputs/igtl_input.hpp"
#include "inputs/igtl_pose_server.hpp"
#include "models/point_registration.hpp"
#include "rigs/simulated_rig.hpp"
#include "runtime/worker_fault.hpp"
#include "tests/support/process_support.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/rigs_for_tests.hpp"
#include "tests/support/leased_run.hpp"

using namespace palprig;
using namespace palprig::test_rigs;
using namespace std::chrono_literals;

namespace {

const std::filesystem::path kTrackedData = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";

TouchSample tracked(double t, std::array<FingerTouch, kFingerCount> fingers) {
  TouchSample s;
  s.t_s = t;
  s.in_contact = true;
  s.own_positions = s.per_finger_force = true;
  s.fingers = fingers;
  s.x_mm = fingers[0].x_mm, s.y_mm = fingers[0].y_mm;
  for (const auto& f : fingers) s.force_N = std::max(s.force_N, f.force_N);
  return s;
}

LoadCellConfig quiet_cells(bool per_finger) {
  LoadCellConfig c;
  c.per_finger = per_finger;
  c.channels.resize(per_finger ? kFingerCount : 1);
  for (auto& ch : c.channels) ch.calibration = {0.1, 2.0};
  c.simulated.noise_sd_V = 0;
  return c;
}

// Records every tick of a run (preallocated: the observer runs on the loop thread).
class FirstRecords final : public TickObserver {
 public:
  explicit FirstRecords(std::size_t capacity) { records.reserve(capacity); }
  void on_tick(const TelemetryRecord& r) noexcept override {
    if (records.size() < records.capacity()) records.push_back(r);
  }
  std::vector<TelemetryRecord> records;
};

// The scene -> tracker transform of the tests (a tracker beside the phantom, turned and upside
// down), and a registration estimated from noisy touches of four fiducials, as a lab gets it.
const RigidTransform& scene_to_tracker() {
  static const RigidTransform t = [] {
    RigidTransform r;
    const double c = std::cos(0.5), s = std::sin(0.5);
    r.rotation = {{{c, -s, 0}, {-s, -c, 0}, {0, 0, -1}}};  // a turn about z, then z into the table
    r.translation_mm = {-150, 40, -200};
    return r;
  }();
  return t;
}

PointRegistration estimated_registration() {
  const std::vector<Vec3_mm> fiducials = {{10, 10, 0}, {150, 10, 0}, {150, 110, 0}, {10, 110, 5}};
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0, 0.2);
  std::vector<Vec3_mm> touched;
  for (const auto& f : fiducials) {
    Vec3_mm p = scene_to_tracker().apply(f);
    for (double& v : p) v += noise(rng);
    touched.push_back(p);
  }
  return register_points(touched, fiducials);
}

// A finger sensor's pose (tracker space) that puts its tip (0, 0, -12 in its frame) at `tip`
// (scene space), tilted a little.
RigidTransform sensor_at(const Vec3_mm& tip, double tilt) {
  RigidTransform in_scene;
  const double c = std::cos(tilt), s = std::sin(tilt);
  in_scene.rotation = {{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
  const Vec3_mm off = in_scene.rotate({0, 0, -12});
  for (int i = 0; i < 3; ++i) in_scene.translation_mm[i] = tip[i] - off[i];
  return scene_to_tracker().after(in_scene);
}

TrackingConfig three_finger_tracking(const RigidTransform& tracker_to_scene) {
  TrackingConfig t;
  t.placement = TrackedPlacement::per_finger;
  for (int i = 0; i < kFingerCount; ++i)
    t.tools.push_back(
        TrackedTool{"Finger" + std::to_string(i + 1) + "ToTracker", i, {{0, 0, -12}, "pivot", std::nan("")}});
  t.registration.tracker_to_scene = tracker_to_scene;
  t.reader_fifo_priority = 0;
  return t;
}

// Three fingers side by side (y spread 16 mm) along a known path at 40 poses a second:
// `path(t)` gives finger 2's tip in scene space.
template <class Path>
std::vector<RecordedPose> three_fingers(double seconds, Path path) {
  std::vector<RecordedPose> rec;
  for (int k = 0; k * 0.025 <= seconds; ++k) {
    const double t = k * 0.025;
    const Vec3_mm mid = path(t);
    for (int i = 0; i < kFingerCount; ++i) {
      const Vec3_mm tip{mid[0], mid[1] + 16.0 * (i - 1), mid[2]};
      rec.push_back(
          RecordedPose{t, "Finger" + std::to_string(i + 1) + "ToTracker", sensor_at(tip, 0.3 * std::sin(t + i))});
    }
  }
  return rec;
}

RigConfig load_cell_rig() {
  RigConfig rig = load_rig_file(kTrackedData / "rigs" / "simulated_load_cells.json");
  rig.load_cells->simulated.noise_sd_V = 0.002;
  return rig;
}

// The rig's tick configuration for a real-time test on a shared machine: the loop is not
// what these tests are about, so lost periods and a late reader do not end them (the killed
// tracker ends its run through the worker fault, at once).
TickConfig patient(const RigConfig& rig) {
  TickConfig c = make_tick_config(rig, {});
  c.safety.max_lost_time_s = 10;
  c.safety.max_consecutive_overruns = 100000;
  c.safety.max_input_age_s = 1.0;
  return c;
}

RunOptions realtime(double seconds, TickObserver* observer) {
  RunOptions opt;
  opt.mode = LoopMode::realtime;
  opt.rate_hz = 1000;
  opt.duration_s = seconds;
  opt.want_fifo = false;
  opt.observer = observer;
  return opt;
}

template <class F>
bool eventually(F&& condition, std::chrono::milliseconds deadline = 5000ms) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(2ms);
  }
  return condition();
}

}  // namespace

TEST(TrackedTick, EachFingerAtItsOwnPositionWithItsOwnForceAndAVentedOneAtZero) {
  const MapScene scene = hard_right_scene();  // hard where x >= 60
  TickConfig cfg;
  TickState st = make_tick_state(cfg);
  // Finger 1 on hard tissue, finger 2 on soft, finger 3 on hard but its tool is out of view.
  const TickResult r =
      tick(st, cfg, scene,
           tracked(0, {FingerTouch{80, 50, -4, 2.0, FingerVent::none}, FingerTouch{10, 50, -4, 2.0, FingerVent::none},
                       FingerTouch{90, 20, -4, 2.0, FingerVent::tool_stale}}),
           0);
  EXPECT_NEAR(r.record.target_kPa[0], 11.75, 0.01);  // paper 002's hard nodule at the reference press
  EXPECT_NEAR(r.record.target_kPa[1], 0.0, 1e-9);
  EXPECT_EQ(r.record.target_kPa[2], 0.0f);
  EXPECT_EQ(r.record.finger_vent[2], FingerVent::tool_stale);
  EXPECT_FLOAT_EQ(r.record.finger_x_mm[0], 80);
  EXPECT_FLOAT_EQ(r.record.finger_y_mm[2], 20);
  EXPECT_EQ(r.record.fault, FaultCode::none);
  EXPECT_TRUE(r.record.flags & kInContact);
  // Each finger's own force: finger 1 pressing twice as hard asks for more.
  TickState st2 = make_tick_state(cfg);
  const TickResult harder =
      tick(st2, cfg, scene,
           tracked(0, {FingerTouch{80, 50, -8, 4.0, FingerVent::none}, FingerTouch{10, 50, 0, 0, FingerVent::none},
                       FingerTouch{0, 0, 0, 0, FingerVent::no_tool}}),
           0);
  EXPECT_NEAR(harder.record.target_kPa[0], 2 * 11.75, 0.02);
  EXPECT_FLOAT_EQ(harder.record.finger_force_N[0], 4.0f);
  EXPECT_EQ(harder.record.finger_vent[2], FingerVent::no_tool);
}

TEST(TrackedTick, ThePenStillPlacesTheTriangleAndBadTrackedValuesFault) {
  const MapScene scene = hard_right_scene();
  TickConfig cfg;
  TickState st = make_tick_state(cfg);
  const TickResult pen = tick(st, cfg, scene, TouchSample{0, 50, 20, 2.0, true}, 0);
  EXPECT_FLOAT_EQ(pen.record.finger_x_mm[1], 66);  // 16 mm along x
  EXPECT_FLOAT_EQ(pen.record.finger_y_mm[2], 36);  // 16 mm along y
  EXPECT_GT(pen.record.target_kPa[1], 11);         // finger 2 over the hard half, as before
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(pen.record.finger_force_N[i], 2.0f);
  TickState bad = make_tick_state(cfg);
  TouchSample s = tracked(0, {FingerTouch{std::nan(""), 50, 0, 2, FingerVent::none}, {}, {}});
  EXPECT_EQ(tick(bad, cfg, scene, s, 0).record.fault, FaultCode::bad_position);
  TickState bad_force = make_tick_state(cfg);
  s = tracked(0, {FingerTouch{1, 1, 0, -1, FingerVent::none}, {}, {}});
  s.force_N = 0;
  EXPECT_EQ(tick(bad_force, cfg, scene, s, 0).record.fault, FaultCode::bad_sample);
}

TEST(TrackedRigStep, TheLoadCellsGiveEachFingerItsForce) {
  const MapScene scene = hard_right_scene();
  SimulatedRig rig(quiet_plants(), 60);
  rig.attach_load_cells(quiet_cells(true));
  rig.open();
  EXPECT_EQ(rig.capabilities().load_cells, 3u);
  RigStep step(TickConfig{}, rig);
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  TouchSample s =
      tracked(0, {FingerTouch{80, 50, -4, 0, FingerVent::none}, FingerTouch{80, 20, -2, 0, FingerVent::none},
                  FingerTouch{80, 80, 3, 0, FingerVent::none}});
  s.force_from_load_cells = true;
  s.per_finger_force = false;  // the step says so from the cells
  const StepResult& r = step.step(scene, s, 0);
  EXPECT_EQ(r.load_cells.count, 3u);
  EXPECT_NEAR(r.tick.record.finger_force_N[0], 2.0, 1e-6);  // 4 mm deep on 0.5 N/mm
  EXPECT_NEAR(r.tick.record.finger_force_N[1], 1.0, 1e-6);
  EXPECT_NEAR(r.tick.record.finger_force_N[2], 0.0, 1e-6);  // above the surface
  EXPECT_GT(r.tick.record.target_kPa[0], r.tick.record.target_kPa[1]);
  EXPECT_EQ(r.tick.record.target_kPa[2], 0.0f);
  EXPECT_FLOAT_EQ(r.tick.record.force_N, 2.0f);

  // One shared cell: the deepest finger's press, for every finger.
  SimulatedRig shared(quiet_plants(), 60);
  shared.attach_load_cells(quiet_cells(false));
  shared.open();
  RigStep one(TickConfig{}, shared);
  ASSERT_EQ(one.arm(), BackendStatus::ok);
  const StepResult& r1 = one.step(scene, s, 0);
  EXPECT_EQ(r1.load_cells.count, 1u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r1.tick.record.finger_force_N[i], 2.0, 1e-6);
}

TEST(TrackedRigStep, ATrackerWithoutLoadCellsFaultsWithTheReason) {
  SimulatedRig rig(quiet_plants(), 60);
  rig.open();
  RigStep step(TickConfig{}, rig);
  ASSERT_EQ(step.arm(), BackendStatus::ok);
  TouchSample s = tracked(0, {FingerTouch{80, 50, -4, 0, FingerVent::none}, {}, {}});
  s.force_from_load_cells = true;
  const StepResult& r = step.step(hard_right_scene(), s, 0);
  EXPECT_TRUE(step.faulted());
  EXPECT_EQ(step.fault(), FaultCode::backend_error);
  EXPECT_NE(step.fault().detail().find("no load cells"), std::string::npos) << step.fault().detail();
  for (float p : r.tick.record.setpoint_kPa) EXPECT_EQ(p, 0.0f);
}

TEST(TrackedEndToEnd, FingersFollowAKnownPathAndTumorBGetsThePressure) {
  clear_worker_faults();
  const SceneFile scene = load_scene_file(kTrackedData / "scenes" / "phantom_abc.json");
  // Finger 2 slides from soft tissue onto tumor B (110, 50) and presses there 4 mm deep;
  // fingers 1 and 3 stay 16 mm to the sides, on soft tissue.
  auto path = [](double t) -> Vec3_mm {
    const double u = std::min(t / 0.6, 1.0);
    const double z = t < 0.6 ? 3.0 : 3.0 - 7.0 * std::min((t - 0.6) / 0.2, 1.0);
    return {140 - 30 * u, 50, z};
  };
  PoseServerOptions options;
  options.port = 0;
  IgtlPoseServer server(three_fingers(2.4, path), options);
  server.start();
  const PointRegistration reg = estimated_registration();
  const RigConfig rig_cfg = load_cell_rig();
  SimulatedRig rig(rig_cfg.plants, rig_cfg.safety.p_max_kPa);
  rig.attach_load_cells(*rig_cfg.load_cells);
  rig.open();
  IgtlInput input({"127.0.0.1", server.port()}, three_finger_tracking(reg.from_to), rig_cfg.safety.max_input_age_s);
  ASSERT_TRUE(eventually([&] { return input.latest(0).fingers[1].vent == FingerVent::none; }));
  FirstRecords rec(4000);
  const RunSummary s =
      palprig::testing::run_loop_leased(patient(rig_cfg), *scene.scene, input, rig, realtime(2.0, &rec));
  EXPECT_EQ(s.fault, FaultCode::none) << s.fault.detail();
  ASSERT_GT(rec.records.size(), 1000u);
  // Every placed finger lies on its known path (each at its own y), within a bound set by the
  // registration's error: the tracker's float32 and the estimated registration's 0.2 mm noise.
  const double bound_mm = std::max(1.0, 4 * reg.fre_mm);
  std::size_t placed = 0, on_b = 0;
  double worst = 0, b_target = 0, soft_target = 0;
  std::size_t soft_n = 0;
  for (const TelemetryRecord& r : rec.records) {
    for (int i = 0; i < kFingerCount; ++i) {
      if (r.finger_vent[i] != FingerVent::none) continue;
      ++placed;
      const double y_expected = 50 + 16.0 * (i - 1);
      const double dx = r.finger_x_mm[i] < 110   ? 110 - r.finger_x_mm[i]
                        : r.finger_x_mm[i] > 140 ? r.finger_x_mm[i] - 140
                                                 : 0;
      worst = std::max(worst, std::hypot(dx, r.finger_y_mm[i] - y_expected));
    }
    if (r.t_s > 1.2 && r.finger_vent[1] == FingerVent::none) {
      ++on_b;
      b_target += r.target_kPa[1];
      soft_target += r.target_kPa[0] + r.target_kPa[2];
      soft_n += 2;
    }
  }
  EXPECT_GT(placed, 2500u);
  EXPECT_LT(worst, bound_mm) << "FRE " << reg.fre_mm << " mm";
  ASSERT_GT(on_b, 500u);
  // Pressing 4 mm on 0.5 N/mm, 2 N, on tumor B: paper 002's 11.75 kPa; soft tissue beside it ~0.
  // The depth, so the force, carries the registration's error along z (a tenth of a millimetre
  // is 0.05 N, 0.3 kPa).
  EXPECT_NEAR(s.force_N[1].max, 2.0, 0.3);
  EXPECT_NEAR(b_target / double(on_b), 11.75 * s.force_N[1].max / 2.0, 0.6);
  EXPECT_GT(b_target / double(on_b), 10.0);
  EXPECT_LT(soft_target / double(soft_n), 1.0);
}

TEST(TrackedEndToEnd, LagCompensationFollowsEachTrackedFingerOverTheStream) {
  // Finger 2 pressed 4 mm (2 N on its load cell) slides across tumor B at 40 mm/s, streamed at
  // 40 poses a second over OpenIGTLink in real time; the whole target lag-compensated with the
  // simulated regulators as calibration identifies them (4 ms + 50 ms) against the same run
  // without: each finger is extrapolated from its own poses, so the tumor's edges arrive nearer
  // their time, and nothing goes above p_max.
  const SceneFile scene = load_scene_file(kTrackedData / "scenes" / "phantom_abc.json");
  auto path = [](double t) -> Vec3_mm { return {150 - 40 * t, 50, -4.0}; };
  const PointRegistration reg = estimated_registration();
  auto run = [&](bool compensate, double& rms_kPa, double& tumor_ratio, double& max_setpoint_kPa, bool& flagged) {
    clear_worker_faults();
    PoseServerOptions options;
    options.port = 0;
    IgtlPoseServer server(three_fingers(2.2, path), options);
    server.start();
    const RigConfig rig_cfg = load_cell_rig();
    SimulatedRig rig(rig_cfg.plants, rig_cfg.safety.p_max_kPa);
    rig.attach_load_cells(*rig_cfg.load_cells);
    rig.open();
    IgtlInput input({"127.0.0.1", server.port()}, three_finger_tracking(reg.from_to), rig_cfg.safety.max_input_age_s);
    ASSERT_TRUE(eventually([&] { return input.latest(0).fingers[1].vent == FingerVent::none; }));
    TickConfig cfg = patient(rig_cfg);
    cfg.lag_compensation.whole_target = compensate;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      cfg.lag_compensation.identified[i] = true;
      cfg.lag_compensation.regulator[i] = {0.004, 0.050, 2000};
    }
    FirstRecords rec(4000);
    const RunSummary s = palprig::testing::run_loop_leased(cfg, *scene.scene, input, rig, realtime(2.0, &rec));
    EXPECT_EQ(s.fault, FaultCode::none) << s.fault.detail();
    double sq = 0, mon = 0, tgt = 0;
    std::size_t n = 0;
    max_setpoint_kPa = 0;
    flagged = false;
    for (const TelemetryRecord& r : rec.records) {
      for (int i = 0; i < kFingerCount; ++i) max_setpoint_kPa = std::max(max_setpoint_kPa, double(r.setpoint_kPa[i]));
      flagged = flagged || (r.flags & kLagCompensated);
      if (r.t_s < 0.3 || r.t_s > 1.9 || r.finger_vent[1] != FingerVent::none || !(r.flags & kInContact)) continue;
      const double d = r.monitor_kPa[1] - r.target_kPa[1];
      sq += d * d;
      ++n;
      if (std::abs(r.finger_x_mm[1] - 110) <= 10 && std::abs(r.finger_y_mm[1] - 50) <= 3)
        mon += r.monitor_kPa[1], tgt += r.target_kPa[1];
    }
    ASSERT_GT(n, 1000u);
    ASSERT_GT(tgt, 0.0);
    rms_kPa = std::sqrt(sq / double(n));
    tumor_ratio = mon / tgt;
  };
  double plain_rms = 0, plain_ratio = 0, plain_max = 0, comp_rms = 0, comp_ratio = 0, comp_max = 0;
  bool plain_flag = true, comp_flag = false;
  run(false, plain_rms, plain_ratio, plain_max, plain_flag);
  run(true, comp_rms, comp_ratio, comp_max, comp_flag);
  RecordProperty("rms_kPa_off_on", std::to_string(plain_rms) + " " + std::to_string(comp_rms));
  RecordProperty("tumor_b_ratio_off_on", std::to_string(plain_ratio) + " " + std::to_string(comp_ratio));
  EXPECT_FALSE(plain_flag);
  EXPECT_TRUE(comp_flag);
  EXPECT_LT(comp_rms, 0.75 * plain_rms) << "RMS " << plain_rms << " -> " << comp_rms << " kPa";
  // The tumor's share reached: better by a margin than without. The goal (>= 0.97) is measured
  // by bench_fidelity in simulated time; here, in real time over a socket, the poses' arrival
  // jitter is in the extrapolation: 0.99 in a release build, 0.89 under ASan on a loaded machine
  // (against 0.79 and less without compensation).
  EXPECT_GT(comp_ratio, plain_ratio + 0.05) << plain_ratio << " -> " << comp_ratio;
  EXPECT_GT(comp_ratio, 0.85) << plain_ratio << " -> " << comp_ratio;
  std::printf("tumor B monitor/target %.3f -> %.3f, RMS %.2f -> %.2f kPa\n", plain_ratio, comp_ratio, plain_rms,
              comp_rms);
  EXPECT_LE(comp_max, 60.0);
}

TEST(TrackedEndToEnd, ThePulseIsFeltOverTheBrachialArtery) {
  clear_worker_faults();
  const SceneFile scene = load_scene_file(kTrackedData / "scenes" / "brachial_pulse.json");
  // Finger 2 over the artery (45, 59), pressing 3.6 mm (1.8 N: inside the 0.6..2.4 N window);
  // finger 3 on the triceps 16 mm away, out of the artery's range.
  auto path = [](double t) -> Vec3_mm { return {45, 59, t < 0.2 ? 3.0 : -3.6}; };
  PoseServerOptions options;
  options.port = 0;
  IgtlPoseServer server(three_fingers(3.0, path), options);
  server.start();
  const RigConfig rig_cfg = load_cell_rig();
  SimulatedRig rig(rig_cfg.plants, rig_cfg.safety.p_max_kPa);
  rig.attach_load_cells(*rig_cfg.load_cells);
  rig.open();
  IgtlInput input({"127.0.0.1", server.port()}, three_finger_tracking(scene_to_tracker().inverse()), 0.1);
  ASSERT_TRUE(eventually([&] { return input.latest(0).fingers[1].vent == FingerVent::none; }));
  FirstRecords rec(4000);
  const RunSummary s =
      palprig::testing::run_loop_leased(patient(rig_cfg), *scene.scene, input, rig, realtime(2.5, &rec));
  EXPECT_EQ(s.fault, FaultCode::none) << s.fault.detail();
  // Over 1.5 s (two beats at 72 BPM) the finger on the artery's target beats; the one beside it is still.
  float lo[3] = {1e9f, 1e9f, 1e9f}, hi[3] = {-1e9f, -1e9f, -1e9f};
  for (const TelemetryRecord& r : rec.records) {
    if (r.t_s < 0.8) continue;
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], r.target_kPa[i]);
      hi[i] = std::max(hi[i], r.target_kPa[i]);
    }
  }
  EXPECT_GT(hi[1] - lo[1], 3.0) << "the pulse under finger 2";
  EXPECT_LT(hi[2] - lo[2], 0.5) << "finger 3, off the artery";
}

TEST(TrackedEndToEnd, ATrackerProcessKilledForRealVentsEveryFinger) {
  clear_worker_faults();
  test_support::TempDir dir;
  // A long recording: the tracker is killed in the middle of it.
  auto path = [](double) -> Vec3_mm { return {110, 50, -4}; };
  std::string csv = "t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw\n";
  for (const RecordedPose& p : three_fingers(30.0, path)) {
    // Quaternion of the rotation (the pose recording's form).
    const Rotation3& r = p.pose.rotation;
    const double w = std::sqrt(std::max(0.0, 1 + r[0][0] + r[1][1] + r[2][2])) / 2;
    const double x = std::copysign(std::sqrt(std::max(0.0, 1 + r[0][0] - r[1][1] - r[2][2])) / 2, r[2][1] - r[1][2]);
    const double y = std::copysign(std::sqrt(std::max(0.0, 1 - r[0][0] + r[1][1] - r[2][2])) / 2, r[0][2] - r[2][0]);
    const double z = std::copysign(std::sqrt(std::max(0.0, 1 - r[0][0] - r[1][1] + r[2][2])) / 2, r[1][0] - r[0][1]);
    char row[200];
    std::snprintf(row, sizeof row, "%.3f,%s,%.4f,%.4f,%.4f,%.7f,%.7f,%.7f,%.7f\n", p.t_s, p.tool.c_str(),
                  p.pose.translation_mm[0], p.pose.translation_mm[1], p.pose.translation_mm[2], x, y, z, w);
    csv += row;
  }
  const auto poses = dir.write("poses.csv", csv);
  palprig::testing::ChildProcess tracker({"igtl-replay", "--poses", poses.string(), "--port", "0"});
  std::smatch m;
  const std::regex listening("listening on port ([0-9]+)");
  ASSERT_TRUE(eventually(
      [&] {
        tracker.pump(10);
        return std::regex_search(tracker.out(), m, listening);
      },
      10000ms))
      << tracker.out() << tracker.err();
  const int port = std::stoi(m[1]);
  const SceneFile scene = load_scene_file(kTrackedData / "scenes" / "phantom_abc.json");
  const RigConfig rig_cfg = load_cell_rig();
  SimulatedRig rig(rig_cfg.plants, rig_cfg.safety.p_max_kPa);
  rig.attach_load_cells(*rig_cfg.load_cells);
  rig.open();
  IgtlInput input({"127.0.0.1", port}, three_finger_tracking(scene_to_tracker().inverse()), 0.1);
  ASSERT_TRUE(eventually([&] { return input.latest(0).fingers[1].vent == FingerVent::none; }));
  FirstRecords rec(20000);
  std::atomic<bool> pressing{false};
  // Kill the tracker once finger 2 presses tumor B: the loop must vent on its own.
  std::thread killer([&] {
    eventually([&] { return pressing.load(); }, 10000ms);
    ::kill(tracker.pid(), SIGKILL);
  });
  struct Watch final : TickObserver {
    FirstRecords& rec;
    std::atomic<bool>& pressing;
    Watch(FirstRecords& r, std::atomic<bool>& p) : rec(r), pressing(p) {}
    void on_tick(const TelemetryRecord& r) noexcept override {
      rec.on_tick(r);
      if (r.setpoint_kPa[1] > 5) pressing.store(true);
    }
  } watch(rec, pressing);
  const RunSummary s =
      palprig::testing::run_loop_leased(patient(rig_cfg), *scene.scene, input, rig, realtime(15.0, &watch));
  killer.join();
  tracker.wait();
  ASSERT_TRUE(pressing.load());
  EXPECT_EQ(s.fault, FaultCode::thread_exception);
  EXPECT_NE(s.fault.detail().find("the server closed the connection"), std::string::npos) << s.fault.detail();
  EXPECT_LT(s.sim_time_s, 14.0);  // it stopped, it did not run on
  // The last record vents every channel; the backend was left vented.
  ASSERT_FALSE(rec.records.empty());
  const TelemetryRecord& last = rec.records.back();
  EXPECT_TRUE(last.flags & kVented);
  for (float p : last.setpoint_kPa) EXPECT_EQ(p, 0.0f);
  EXPECT_FALSE(rig.armed());
  clear_worker_faults();
}
