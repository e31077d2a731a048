// Calibration speed: the goal is that fitting 10k samples with Ceres takes under a second.
//   BM_FitHysteresis/N           the full identification (exact grid stage + Ceres threshold
//                                refinement) on N quasi-static samples, 8 operators
//   BM_FitHysteresisGridOnly/N   stage 1 alone (thresholds fixed on the grid)
//   BM_FitHysteresisRobust/N     with a Cauchy loss (reweighted stage 1, robust Ceres stage)
//   BM_FitLine/N                 one branch regression
//   BM_InverseModelPerSample     the tick's cost of applying a fitted inverse (8 operators)
//   BM_SweepSimulatedRig         paper 002's staircase (5 repeats) on the simulated rig
//   BM_EvaluateSimulatedRig      `calibrate evaluate`: 2 x 120 s at 1 kHz on simulated time
// Run: build/bench/bench_calibration (or bench/run_all.sh build).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "controller/backend_factory.hpp"
#include "calibration/compensation_evaluation.hpp"
#include "calibration/hysteresis_fit.hpp"
#include "calibration/line_fit.hpp"
#include "calibration/sweep_plan.hpp"
#include "calibration/sweep_runner.hpp"
#include "formats/rig_file.hpp"
#include "controller/rig_lease.hpp"

using namespace palprig;

namespace {

// Reversals of many sizes in 0..60 kPa, through a known PI model plus 0.1 kPa of noise.
struct Synthetic {
  std::vector<double> x, y;
  explicit Synthetic(std::size_t n) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> level(0, 60);
    std::normal_distribution<double> noise(0, 0.1);
    x.push_back(0);
    double goal = level(rng);
    while (x.size() < n) {
      const double cur = x.back();
      if (std::abs(goal - cur) < 1e-9) {
        goal = level(rng);
        continue;
      }
      x.push_back(cur + std::clamp(goal - cur, -2.0, 2.0));
    }
    PrandtlIshlinskii m;
    m.linear_weight = 0.4;
    m.operator_count = 3;
    m.thresholds_kPa = {0.8, 2.1, 3.7};
    m.weights = {0.25, 0.2, 0.15};
    y.resize(n);
    simulate_hysteresis(m, x, y);
    for (double& v : y) v += noise(rng);
  }
};

void fit(benchmark::State& state, HysteresisFitOptions o) {
  const Synthetic data(static_cast<std::size_t>(state.range(0)));
  HysteresisFit last;
  for (auto _ : state) {
    last = fit_hysteresis(data.x, data.y, o, "bench", "synthetic");
    benchmark::DoNotOptimize(last);
  }
  state.counters["rms_kPa"] = last.rms_error_kPa;
  state.counters["iterations"] = last.iterations;
  state.counters["converged"] = last.converged;
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_FitHysteresis(benchmark::State& state) { fit(state, {}); }
void BM_FitHysteresisGridOnly(benchmark::State& state) {
  HysteresisFitOptions o;
  o.refine_thresholds = false;
  fit(state, o);
}
void BM_FitHysteresisRobust(benchmark::State& state) {
  HysteresisFitOptions o;
  o.loss = RobustLoss::cauchy;
  o.loss_scale_kPa = 0.3;
  fit(state, o);
}

void BM_FitLine(benchmark::State& state) {
  const Synthetic data(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(fit_line(data.x, data.y, "bench", "line"));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_InverseModelPerSample(benchmark::State& state) {
  const Synthetic data(10000);
  HysteresisFitOptions o;
  o.refine_thresholds = false;
  o.min_linear_weight = 0.01;
  PrandtlIshlinskii inverse = fit_hysteresis(data.x, data.y, o, "bench", "inverse").model;
  inverse.operator_count = 8;  // the tick's worst case with the default operator count
  for (std::size_t i = 0; i < 8; ++i) {
    inverse.thresholds_kPa[i] = 0.5 * double(i + 1);
    inverse.weights[i] = 0.1;
  }
  inverse = inverse.inverse();
  inverse.reset(0);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(inverse.apply(data.x[k]));
    k = (k + 1) % data.x.size();
  }
}

RigConfig bench_rig() { return load_rig_file(std::string(PALPRIG_SOURCE_DIR) + "/data/rigs/simulated.json"); }

struct NullSink final : SweepSink {
  std::size_t samples = 0;
  void on_hold(std::size_t, const SweepHold&, std::span<const SweepSample> s, const HoldOutcome&) override {
    samples += s.size();
  }
};

void BM_SweepSimulatedRig(benchmark::State& state) {
  const RigConfig rig = bench_rig();
  const SweepSchedule plan = plan_calibration_sweep({}, rig.safety.p_max_kPa);
  SweepRunOptions o;
  o.realtime = false;
  double rig_seconds = 0;
  for (auto _ : state) {
    std::unique_ptr<Rig> opened = open_rig(rig);
    RigLease lease = opened->lease("the sweep benchmark");
    NullSink sink;
    rig_seconds = run_calibration_sweep(lease, plan, o, sink).duration_s;
  }
  state.counters["rig_s"] = rig_seconds;
}

void BM_EvaluateSimulatedRig(benchmark::State& state) {
  const RigConfig rig = bench_rig();
  CalibrationModels cal;
  for (auto& h : cal.hysteresis) {
    h.linear_weight = 0.01;
    h.operator_count = 1;
    h.thresholds_kPa[0] = 2.0;
    h.weights[0] = 0.99;
  }
  EvaluationOptions o;
  o.realtime = false;
  double improvement = 0;
  for (auto _ : state) {
    std::unique_ptr<Rig> opened = open_rig(rig);
    RigLease lease = opened->lease("the evaluation benchmark");
    improvement = evaluate_compensation(lease, rig, cal, o).worst_improvement;
  }
  state.counters["improvement"] = improvement;
}

}  // namespace

BENCHMARK(BM_FitHysteresis)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FitHysteresisGridOnly)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FitHysteresisRobust)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FitLine)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_InverseModelPerSample);
BENCHMARK(BM_SweepSimulatedRig)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EvaluateSimulatedRig)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
