// Cost of function scenes on the 1 kHz path: one finger's felt stiffness on each shipped scene,
// a whole tick with the pulse stage (three fingers, lag compensation; with the number of heap
// allocations it made, which must be 0), and one compensator step. Tracked fingers:
// a rig step with each finger at its own position and its own simulated load cell, and the
// tracker input's latest() while a real OpenIGTLink server streams to its reader thread (the
// allocations counted on the loop's own thread: the reader and the server allocate on theirs).
//   build/bin/bench_scene_sample
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>
#include <map>
#include <new>
#include <string>

#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "controller/rig_step.hpp"
#include "controller/tick.hpp"
#include "inputs/igtl_input.hpp"
#include "inputs/igtl_pose_server.hpp"
#include "models/pulse_renderer.hpp"
#include "rigs/simulated_rig.hpp"

using namespace palprig;

// Every allocation in this program is counted, so the tick benchmark can report how many it
// made (the loop path must make none). This program only: each bench file is its own binary.
// GCC pairs the replaced operator new with std::free once both are inlined and warns of a
// mismatch; here new is malloc, so the pair is right.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
static std::atomic<long> g_allocations{0};
static thread_local long t_allocations = 0;  // this thread's own
void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  ++t_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

const std::string kData = std::string(PALPRIG_SOURCE_DIR) + "/data/";

const Scene& scene(const std::string& name) {
  static std::map<std::string, SceneFile> loaded;
  auto it = loaded.find(name);
  if (it == loaded.end()) it = loaded.emplace(name, load_scene_file(kData + "scenes/" + name + ".json")).first;
  return *it->second.scene;
}

// A finger moving over the scene (so the broad phase sees different inclusions), pressing 2 N.
void BM_FeltStiffness(benchmark::State& state, const std::string& name) {
  const Scene& s = scene(name);
  const SceneBounds b = s.bounds();
  double x = b.x0_mm, t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.sample({x, 0.5 * (b.y0_mm + b.y1_mm)}, 2.0, t));
    x += 0.37;
    if (x > b.x1_mm) x = b.x0_mm;
    t += 0.001;
  }
}
BENCHMARK_CAPTURE(BM_FeltStiffness, phantom, std::string("phantom_abc_function"));
BENCHMARK_CAPTURE(BM_FeltStiffness, liver_breathing, std::string("liver_edge"));
BENCHMARK_CAPTURE(BM_FeltStiffness, groin, std::string("groin_femoral"));
BENCHMARK_CAPTURE(BM_FeltStiffness, brachial, std::string("brachial_pulse"));
BENCHMARK_CAPTURE(BM_FeltStiffness, map_phantom, std::string("phantom_abc"));

// A full tick on the brachial scene with two fingers over the pulsing artery.
void BM_TickWithPulse(benchmark::State& state) {
  const Scene& s = scene("brachial_pulse");
  const TickConfig cfg = make_tick_config(load_rig_file(kData + "rigs/simulated.json"), CalibrationModels{});
  TickState st = make_tick_state(cfg);
  double t = 0;
  const long before = g_allocations.load();
  for (auto _ : state) {
    benchmark::DoNotOptimize(tick(st, cfg, s, {t, 24, 59, 2.0, true}, t));
    t += 0.001;
  }
  state.counters["allocations"] = double(g_allocations.load() - before);  // expected 0
}
BENCHMARK(BM_TickWithPulse);

// A rig step with tracked fingers on the brachial scene: fingers 1 and 2 along the artery, each
// at its own position, 3.6 mm deep; the force of each from its own simulated load cell.
void BM_TrackedRigStep(benchmark::State& state) {
  const Scene& s = scene("brachial_pulse");
  const RigConfig rig_cfg = load_rig_file(kData + "rigs/simulated_load_cells.json");
  SimulatedRig rig(rig_cfg.plants, rig_cfg.safety.p_max_kPa);
  rig.attach_load_cells(*rig_cfg.load_cells);
  rig.open();
  RigStep step(make_tick_config(rig_cfg, CalibrationModels{}), rig);
  step.arm();
  TouchSample sample;
  sample.in_contact = sample.own_positions = sample.force_from_load_cells = true;
  sample.fingers = {FingerTouch{24, 59.5, -3.6, 0, FingerVent::none}, FingerTouch{40, 59.2, -3.6, 0, FingerVent::none},
                    FingerTouch{40, 80, -3.6, 0, FingerVent::none}};
  double t = 0;
  const long before = t_allocations;
  for (auto _ : state) {
    sample.t_s = t;
    benchmark::DoNotOptimize(step.step(s, sample, t));
    t += 0.001;
  }
  state.counters["allocations"] = double(t_allocations - before);  // expected 0
}
BENCHMARK(BM_TrackedRigStep);

// The tracker input as the loop reads it, while a server on loopback streams three tools at
// 200 poses a second each to the input's reader thread.
void BM_TrackerLatest(benchmark::State& state) {
  std::vector<RecordedPose> rec;
  for (int k = 0; k < 2000; ++k)
    for (int f = 0; f < 3; ++f) {
      RecordedPose p;
      p.t_s = k * 0.005;
      p.tool = "Finger" + std::to_string(f + 1) + "ToTracker";
      p.pose.translation_mm = {30.0 + 16 * f, 60, -3};
      rec.push_back(p);
    }
  IgtlPoseServer server(rec, PoseServerOptions{0, false, true});
  server.start();
  TrackingConfig tracking;
  tracking.placement = TrackedPlacement::per_finger;
  for (int f = 0; f < 3; ++f)
    tracking.tools.push_back(TrackedTool{"Finger" + std::to_string(f + 1) + "ToTracker", f, {}});
  tracking.reader_fifo_priority = 0;
  {
    IgtlInput input({"127.0.0.1", server.port()}, tracking, 0.1);
    double t = 0;
    const long before = t_allocations;
    for (auto _ : state) {
      benchmark::DoNotOptimize(input.latest(t));
      t += 1e-6;
    }
    state.counters["allocations"] = double(t_allocations - before);  // expected 0
  }
  server.stop();
}
BENCHMARK(BM_TrackerLatest);

void BM_LagCompensatorEdge(benchmark::State& state) {
  // The costly case: every step is an edge (the bisection runs).
  LagCompensator c;
  const RegulatorLag lag;
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.command(lag, (k++ / 20) % 2 ? 8.0 : 0.0, -4.0, 56.0, 2.0, 0.001));
  }
}
BENCHMARK(BM_LagCompensatorEdge);

}  // namespace

BENCHMARK_MAIN();
