// Psychophysics: psychometric fit time for 10,000 trials, parametric-bootstrap time
// for 1,000 resamples, and how well the shipped staircase and QUEST protocols recover the
// simulated observer's analytic threshold over 20 seeded participants on the simulated rig
// (counters: bias and spread in % of the analytic threshold, trials per track).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "controller/backend_factory.hpp"
#include "controller/tick_setup.hpp"
#include "study/random_source.hpp"
#include "experiments/rig_stimulus.hpp"
#include "experiments/threshold_observer.hpp"
#include "experiments/threshold_session.hpp"
#include "formats/rig_file.hpp"
#include "statistics/psychometric_fit.hpp"

namespace {

using namespace palprig;

// 10,000 yes/no trials of a cumulative Gaussian (PSE 2 kPa, sd 0.6 kPa, lapse 2 %), at `levels`
// distinct levels spread over 0..4 kPa.
std::pair<std::vector<double>, std::vector<int>> trials(int levels) {
  RandomSource random(17);
  std::vector<double> x;
  std::vector<int> r;
  for (int i = 0; i < 10000; ++i) {
    const double level =
        levels >= 10000 ? 4.0 * random.uniform() : 4.0 * static_cast<double>(random.below(levels)) / (levels - 1);
    const double p = stats::psychometric_value(stats::Sigmoid::cumulative_gaussian, 2.0, 0.6, 0.0, 0.02, level);
    x.push_back(level);
    r.push_back(random.uniform() < p ? 1 : 0);
  }
  return {x, r};
}

void BM_FitTenThousandTrials(benchmark::State& state) {
  const auto [x, r] = trials(static_cast<int>(state.range(0)));
  stats::PsychometricOptions o;
  o.bootstrap = 0;  // guess 0, lapse fitted
  for (auto _ : state) {
    const auto fit = stats::fit_psychometric(stats::counts_per_level(x, r), o);
    benchmark::DoNotOptimize(fit.threshold);
  }
  state.counters["levels"] = static_cast<double>(stats::counts_per_level(x, r).size());
}
BENCHMARK(BM_FitTenThousandTrials)->Arg(81)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_Bootstrap1000(benchmark::State& state) {
  const int n_trials = static_cast<int>(state.range(0));
  auto [x, r] = trials(81);
  x.resize(static_cast<std::size_t>(n_trials));
  r.resize(static_cast<std::size_t>(n_trials));
  const auto counts = stats::counts_per_level(x, r);
  stats::PsychometricOptions o;
  o.bootstrap = 1000;
  for (auto _ : state) {
    const auto fit = stats::fit_psychometric(counts, o);
    benchmark::DoNotOptimize(fit.threshold_ci.low);
  }
  state.counters["trials"] = n_trials;
  state.counters["levels"] = static_cast<double>(counts.size());
}
BENCHMARK(BM_Bootstrap1000)->Arg(200)->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(1);

void recovery(benchmark::State& state, const char* protocol_file, double target_p) {
  const ThresholdProtocol p =
      load_threshold_protocol(std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "protocols" / protocol_file);
  const RigConfig rig = load_rig_file(std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "rigs" / "simulated.json");
  const TickConfig config = make_tick_config(rig, CalibrationModels{});
  ThresholdObserverModel model;
  constexpr int kParticipants = 20;
  std::vector<std::vector<double>> estimates(p.tracks.size());
  std::vector<double> trials_per_track(p.tracks.size(), 0.0);
  for (auto _ : state) {
    for (int seed = 1; seed <= kParticipants; ++seed) {
      auto backend = make_backend(rig);
      backend->open();
      RigStimulus output(config, *backend);
      model.seed = static_cast<std::uint64_t>(state.range(0)) + static_cast<std::uint64_t>(seed);
      SimulatedThresholdObserver observer(model);
      std::vector<AdaptiveTrack> tracks;
      for (const auto& spec : p.tracks) tracks.emplace_back(spec);
      SimulatedClock clock;
      ThresholdSessionOptions options;
      options.seed = static_cast<std::uint64_t>(state.range(0)) + static_cast<std::uint64_t>(seed);
      run_threshold_session(p, tracks, output, observer, clock, options);
      for (std::size_t t = 0; t < tracks.size(); ++t) {
        estimates[t].push_back(tracks[t].estimate().threshold_kPa);
        trials_per_track[t] += tracks[t].trials();
      }
    }
  }
  for (std::size_t t = 0; t < p.tracks.size(); ++t) {
    const double truth = analytic_threshold_kPa(model, p.method, p.tracks[t].fingers, target_p);
    double mean = 0, ss = 0;
    for (double e : estimates[t]) mean += e / estimates[t].size();
    for (double e : estimates[t]) ss += (e - mean) * (e - mean);
    const double sd = std::sqrt(ss / (estimates[t].size() - 1));
    const std::string name = p.tracks[t].name;
    state.counters[name + "_analytic_kPa"] = truth;
    state.counters[name + "_mean_kPa"] = mean;
    state.counters[name + "_bias_pct"] = 100 * (mean / truth - 1);
    state.counters[name + "_sd_pct"] = 100 * sd / truth;
    state.counters[name + "_trials"] = trials_per_track[t] / static_cast<double>(estimates[t].size());
  }
}

void BM_StaircaseRecovery20(benchmark::State& state) {
  recovery(state, "threshold_1up3down.json", std::pow(0.5, 1.0 / 3.0));
}
void BM_QuestRecovery20(benchmark::State& state) { recovery(state, "threshold_quest.json", 0.82); }
// The argument is the seed base: three independent panels of 20 participants each.
BENCHMARK(BM_StaircaseRecovery20)->Arg(0)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_QuestRecovery20)->Arg(0)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
