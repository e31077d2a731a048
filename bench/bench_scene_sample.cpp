// Cost of function scenes on the 1 kHz path: one finger's felt stiffness on each shipped scene,
// a whole tick with the pulse stage (three fingers, lag compensation; with the number of heap
// allocations it made, which must be 0), and one compensator step.
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
#include "controller/tick.hpp"
#include "models/pulse_renderer.hpp"

using namespace palprig;

// Every allocation in this program is counted, so the tick benchmark can report how many it
// made (the loop path must make none). This program only: each bench file is its own binary.
// GCC pairs the replaced operator new with std::free once both are inlined and warns of a
// mismatch; here new is malloc, so the pair is right.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
static std::atomic<long> g_allocations{0};
void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
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
