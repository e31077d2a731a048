// Tick cost and replay throughput (goal: tick p99 <= 2 us with 3 fingers on a
// 4096 x 4096 map; replay >= 1000x real time at 1 kHz).
//   build/bin/bench_tick                      all benchmarks
// Per-tick percentiles are reported as counters (p50_ns, p99_ns, p999_ns), each tick timed on
// CLOCK_MONOTONIC around the tick call (the clock read itself costs ~20 ns and is included).
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "controller/tick_setup.hpp"
#include "formats/calibration_file.hpp"
#include "controller/loop_runner.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "controller/tick.hpp"
#include "inputs/input_source.hpp"
#include "controller/rig_lease.hpp"
#include "models/tissue_scene.hpp"

using namespace palprig;

namespace {

std::int64_t now_ns() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

const MapScene& big_scene(MapSampling sampling) {
  static std::vector<float> values = [] {
    std::vector<float> v(std::size_t{4096} * 4096);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    for (auto& x : v) x = u(rng);
    return v;
  }();
  static MapScene nearest(StiffnessMap(4096, 4096, 400.0, 400.0, values), MapSampling::nearest);
  static MapScene bilinear(StiffnessMap(4096, 4096, 400.0, 400.0, values), MapSampling::bilinear);
  return sampling == MapSampling::nearest ? nearest : bilinear;
}

// The tick times' p50, p99, p99.9 and maximum as the benchmark's counters.
void report_percentiles(benchmark::State& state, std::vector<std::int64_t>& ns) {
  std::sort(ns.begin(), ns.end());
  auto pct = [&](double q) {
    return ns.empty() ? 0.0 : double(ns[std::min(ns.size() - 1, std::size_t(q * ns.size()))]);
  };
  state.counters["p50_ns"] = pct(0.50);
  state.counters["p99_ns"] = pct(0.99);
  state.counters["p999_ns"] = pct(0.999);
  state.counters["max_ns"] = ns.empty() ? 0.0 : double(ns.back());
}

// A pen wandering over the whole map (a new place each tick: the worst case for the cache)
// or moving like a hand (40 mm/s).
// With lag_compensated, the whole target is lag-compensated (the regulators of the simulated
// rig as calibration identifies them: 4 ms dead time, 50 ms lag): the scene is also sampled
// where the fingers will be (up to three more samples per finger), and every channel's
// compensator runs; on the random map every tick is an edge, its worst case.
// With asymmetric, the regulator is the shipped asymmetric one as calibration identifies it
// (data/rigs/simulated_asymmetric.json: 3.7 ms dead time, 40 ms fill and 86 ms exhaust lag, five
// asymmetric plays whose inverse the tick solves at the actuator's state).
// With exhaust_near_0, its exhaust lag also grows near 0 kPa as calibration now identifies it on
// that regulator (55.4 ms far from 0 kPa, 2.10 times slower at 0, scale 33.4 kPa; fill 39.5 ms).
void tick_cost(benchmark::State& state, MapSampling sampling, bool wandering, bool lag_compensated = false,
               bool asymmetric = false, bool exhaust_near_0 = false) {
  const MapScene& scene = big_scene(sampling);
  TickConfig cfg;
  if (lag_compensated) {
    cfg.lag_compensation.whole_target = true;
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      cfg.lag_compensation.identified[i] = true;
      cfg.lag_compensation.regulator[i] = {0.004, 0.050, 2000.0};
      if (asymmetric) cfg.lag_compensation.regulator[i] = {0.0037, 0.040, 2000.0, 0.086};
      if (exhaust_near_0) cfg.lag_compensation.regulator[i] = {0.0041, 0.0395, 2000.0, 0.0554, 2.10, 33.4};
    }
  }
  if (asymmetric) {
    PrandtlIshlinskii h;
    h.linear_weight = 0.037;
    h.operator_count = 5;
    h.asymmetric = true;
    h.thresholds_kPa = {1.20, 2.95, 3.80, 42.99, 4.94};
    h.falling_thresholds_kPa = {2.59, 1.00, 0.43, 0.05, 6.38};
    h.weights = {0.005, 0.755, 0.184, 0.013, 0.008};
    cfg.hysteresis_model.fill(h);
  }
  TickState st = make_tick_state(cfg);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> pos(0, 400);
  const std::size_t n_samples = 1 << 16;
  std::vector<TouchSample> samples(n_samples);
  for (std::size_t i = 0; i < n_samples; ++i) {
    const double t = double(i) * 1e-3;
    samples[i] = wandering ? TouchSample{t, pos(rng), pos(rng), 2.0, true}
                           : TouchSample{t, 20 + std::fmod(40 * t, 360), 200 + 50 * std::sin(t), 2.0, true};
  }
  std::vector<std::int64_t> ns;
  ns.reserve(4'000'000);
  std::size_t i = 0;
  double t = 0;
  for (auto _ : state) {
    const TouchSample& s0 = samples[i++ & (n_samples - 1)];
    TouchSample s = s0;
    s.t_s = t;
    const std::int64_t a = now_ns();
    TickResult r = tick(st, cfg, scene, s, t);
    const std::int64_t b = now_ns();
    benchmark::DoNotOptimize(r);
    if (ns.size() < ns.capacity()) ns.push_back(b - a);
    t += 1e-3;
  }
  report_percentiles(state, ns);
}

void BM_TickNearestWandering(benchmark::State& s) { tick_cost(s, MapSampling::nearest, true); }
void BM_TickBilinearWandering(benchmark::State& s) { tick_cost(s, MapSampling::bilinear, true); }
void BM_TickNearestHandSpeed(benchmark::State& s) { tick_cost(s, MapSampling::nearest, false); }
void BM_TickNearestWanderingLagCompensated(benchmark::State& s) { tick_cost(s, MapSampling::nearest, true, true); }
void BM_TickNearestHandSpeedLagCompensated(benchmark::State& s) { tick_cost(s, MapSampling::nearest, false, true); }
void BM_TickNearestWanderingAsymmetricRegulator(benchmark::State& s) {
  tick_cost(s, MapSampling::nearest, true, true, true);
}
void BM_TickNearestHandSpeedAsymmetricRegulator(benchmark::State& s) {
  tick_cost(s, MapSampling::nearest, false, true, true);
}
void BM_TickNearestWanderingAsymmetricExhaustNear0(benchmark::State& s) {
  tick_cost(s, MapSampling::nearest, true, true, true, true);
}
void BM_TickNearestHandSpeedAsymmetricExhaustNear0(benchmark::State& s) {
  tick_cost(s, MapSampling::nearest, false, true, true, true);
}
BENCHMARK(BM_TickNearestWandering);
BENCHMARK(BM_TickBilinearWandering);
BENCHMARK(BM_TickNearestHandSpeed);
BENCHMARK(BM_TickNearestWanderingLagCompensated);
BENCHMARK(BM_TickNearestHandSpeedLagCompensated);
BENCHMARK(BM_TickNearestWanderingAsymmetricRegulator);
BENCHMARK(BM_TickNearestHandSpeedAsymmetricRegulator);
BENCHMARK(BM_TickNearestWanderingAsymmetricExhaustNear0);
BENCHMARK(BM_TickNearestHandSpeedAsymmetricExhaustNear0);

// The bundled phantom (paper 002's tumors A, B, C: a 161 x 121 map) under the demo's recorded
// pen pass at 1 kHz, with the shipped simulated rig's calibration (its identified regulator
// dynamics): the tick as the demo runs it, without and with the whole target lag-compensated.
void phantom_pass_cost(benchmark::State& state, bool lag_compensated) {
  const std::filesystem::path data = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";
  static const SceneFile scene = load_scene_file(data / "scenes" / "phantom_abc.json");
  CalibrationModels cal = load_calibration_file(data / "calibration" / "sim-default.json");
  cal.lag_compensation.enabled = lag_compensated;
  const TickConfig cfg = make_tick_config(load_rig_file(data / "rigs" / "simulated.json"), cal);
  TraceInput trace(load_trace_csv(data / "traces" / "phantom_abc_pass.csv", cfg.contact_force_N), "pass",
                   cfg.contact_force_N);
  const auto ticks = static_cast<std::size_t>(trace.duration_s() * 1000);
  std::vector<TouchSample> samples(ticks);
  for (std::size_t i = 0; i < ticks; ++i) samples[i] = trace.latest(double(i) * 1e-3);
  TickState st = make_tick_state(cfg);
  std::vector<std::int64_t> ns;
  ns.reserve(4'000'000);
  std::size_t i = 0;
  double t = 0;
  for (auto _ : state) {
    if (i == ticks) {  // the pass again from the start, as a new run
      i = 0;
      t = 0;
      st = make_tick_state(cfg);
    }
    const TouchSample& s = samples[i++];
    const std::int64_t a = now_ns();
    TickResult r = tick(st, cfg, *scene.scene, s, t);
    const std::int64_t b = now_ns();
    benchmark::DoNotOptimize(r);
    if (ns.size() < ns.capacity()) ns.push_back(b - a);
    t += 1e-3;
  }
  report_percentiles(state, ns);
}
void BM_TickPhantomPass(benchmark::State& s) { phantom_pass_cost(s, false); }
void BM_TickPhantomPassLagCompensated(benchmark::State& s) { phantom_pass_cost(s, true); }
BENCHMARK(BM_TickPhantomPass);
BENCHMARK(BM_TickPhantomPassLagCompensated);

// A function scene rendered from the finite-element table (data/scenes/fe_depths.json: two tumors
// 5 and 15 mm down) against the same scene with the stiffness rule: the pen sweeps across both
// tumors and back at hand speed (120 mm in 2 s), pressing 2 N, shipped calibration.
void fe_table_cost(benchmark::State& state, bool table) {
  const std::filesystem::path data = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";
  static SceneFile scene = load_scene_file(data / "scenes" / "fe_depths.json");
  // A copy of the shipped table: the scene's own goes when the rule is switched on.
  static const FeStressTable kept = *dynamic_cast<FunctionScene&>(*scene.scene).fe_table();
  auto& fs = dynamic_cast<FunctionScene&>(*scene.scene);
  fs.use_fe_table(table ? std::make_shared<const FeStressTable>(kept) : nullptr);
  const TickConfig cfg = make_tick_config(load_rig_file(data / "rigs" / "simulated.json"),
                                          load_calibration_file(data / "calibration" / "sim-default.json"));
  TickState st = make_tick_state(cfg);
  std::vector<std::int64_t> ns;
  ns.reserve(4'000'000);
  double t = 0;
  for (auto _ : state) {
    const double u = std::fmod(t, 4.0) / 4.0;  // there and back in 4 s
    TouchSample s;
    s.t_s = t;
    s.x_mm = 20 + 120 * (u < 0.5 ? 2 * u : 2 - 2 * u);
    s.y_mm = 40;
    s.force_N = 2.0;
    s.in_contact = true;
    const std::int64_t a = now_ns();
    TickResult r = tick(st, cfg, *scene.scene, s, t);
    const std::int64_t b = now_ns();
    benchmark::DoNotOptimize(r);
    if (ns.size() < ns.capacity()) ns.push_back(b - a);
    t += 1e-3;
  }
  report_percentiles(state, ns);
}
void BM_TickFunctionSceneFeTable(benchmark::State& s) { fe_table_cost(s, true); }
void BM_TickFunctionSceneStiffnessRule(benchmark::State& s) { fe_table_cost(s, false); }
BENCHMARK(BM_TickFunctionSceneFeTable);
BENCHMARK(BM_TickFunctionSceneStiffnessRule);

// Replay: the bundled phantom rastered for 60 s of loop time at 1 kHz on the simulated rig.
void BM_Replay60s(benchmark::State& state) {
  const bool with_telemetry = state.range(0) != 0;
  const std::filesystem::path data = std::filesystem::path(PALPRIG_SOURCE_DIR) / "data";
  const SceneFile scene = load_scene_file(data / "scenes" / "phantom_abc.json");
  const RigConfig rig = load_rig_file(data / "rigs" / "simulated.json");
  const TickConfig cfg = make_tick_config(rig, CalibrationModels{});
  double speedup_sum = 0;
  int runs = 0;
  for (auto _ : state) {
    SimulatedRig backend(rig.plants, rig.safety.p_max_kPa);
    backend.open();
    RasterInput raster(scene.scene->bounds(), RasterPlan{});
    RunOptions opt;
    opt.duration_s = 60;
    opt.mode = LoopMode::replay;
    if (with_telemetry) opt.telemetry_path = std::filesystem::temp_directory_path() / "palprig-bench-telemetry.bin";
    Rig bench_rig(backend, "the benchmark's simulated rig");
    RigLease lease = bench_rig.lease("the replay benchmark");
    const RunSummary s = run_loop(cfg, *scene.scene, raster, lease, opt);
    speedup_sum += s.sim_time_s / s.wall_time_s;
    ++runs;
  }
  state.counters["x_realtime"] = speedup_sum / runs;
  state.counters["ticks_per_s"] = benchmark::Counter(60000.0 * runs, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Replay60s)->Arg(0)->Arg(1)->ArgNames({"telemetry_bin"})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
