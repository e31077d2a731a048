// A study's cost grows linearly with its trials.
//   ThresholdStoreGrowth  a 20,000-trial QUEST track (the session bound) committed trial by
//                         trial into a fresh SQLite store, as a session commits them: bytes
//                         of the database per trial over the first and the last 1,000 trials
//                         (constant: the tracks are replayed from the rows, schema 3), and
//                         what one row's copy of the track state would have weighed under
//                         schema 2 at the last trial; commit time per trial
//   PlanLongSession       planning 8 combinations x 2,500 repetitions (20,000 trials, at most
//                         1 in a row), and 1,000 repetitions (8,000 trials, 7 s before)
// Run: build/bin/bench_linear_study (figures in docs/analysing.md, "A store grows linearly").
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "store/threshold_store.hpp"
#include "study/random_source.hpp"
#include "study/threshold_protocol.hpp"
#include "study/threshold_record.hpp"
#include "study/trial_order.hpp"

namespace {

using namespace palprig;
namespace fs = std::filesystem;

// The shipped QUEST protocol with one track and max_trials at the session bound.
ThresholdProtocol long_quest_protocol(const fs::path& dir) {
  nlohmann::json doc;
  std::ifstream(fs::path(PALPRIG_SOURCE_DIR) / "data" / "protocols" / "threshold_quest.json") >> doc;
  doc["tracks"] = nlohmann::json::array({doc["tracks"][0]});
  doc["tracks"][0]["quest"]["max_trials"] = 20000;
  const fs::path file = dir / "long_quest.json";
  std::ofstream(file) << doc.dump(2);
  return load_threshold_protocol(file);
}

std::int64_t database_bytes(SqliteTrialStore& store) {
  return store.database().pragma_integer("page_count") * store.database().pragma_integer("page_size");
}

void ThresholdStoreGrowth(benchmark::State& state) {
  const int trials = static_cast<int>(state.range(0));
  const fs::path dir = fs::temp_directory_path() / ("palprig-bench-linear-" + std::to_string(::getpid()));
  for (auto _ : state) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const ThresholdProtocol protocol = long_quest_protocol(dir);
    SqliteTrialStore store(dir / "long.db", TrialStore::Access::read_write);
    ThresholdStore threshold(store);
    const ParticipantRecord who = store.enrol("sim:1", true);
    const std::int64_t session = threshold.create_session(who, protocol, 1, SessionSetup{"bench", "simulated", "none"});
    std::vector<AdaptiveTrack> tracks;
    for (const TrackSpec& spec : protocol.tracks) tracks.emplace_back(spec);
    RandomSource random(7);
    const double true_threshold_kPa = 1.0;
    std::int64_t bytes_at_1000 = 0, bytes_before_last_1000 = 0;
    double commit_s = 0;
    for (int position = 0; position < trials; ++position) {
      ThresholdTrialRecord r;
      r.position = position;
      r.track = 0;
      r.track_name = protocol.tracks[0].name;
      r.fingers = "one";
      r.level_kPa = tracks[0].next_level_kPa();
      r.reference_kPa = protocol.reference_kPa;
      r.answered = true;
      r.response = 1;
      const double p =
          tracks[0].spec().quest.gamma +
          (1 - tracks[0].spec().quest.gamma) * (1 - std::exp(-std::pow(r.level_kPa / true_threshold_kPa, 3.5)));
      r.correct = static_cast<double>(random.below(1000000)) / 1e6 < p;
      r.reversal = tracks[0].record(r.level_kPa, r.correct);
      r.onset_s = position * 3.0;
      r.response_time_s = 0.5;
      r.felt_kPa = {8.0, 8.0 + r.level_kPa};
      const auto t0 = std::chrono::steady_clock::now();
      threshold.commit_trial(session, r);
      commit_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (position + 1 == 1000) bytes_at_1000 = database_bytes(store);
      if (position + 1 == trials - 1000) bytes_before_last_1000 = database_bytes(store);
    }
    const std::int64_t bytes_end = database_bytes(store);
    state.counters["bytes_per_trial_first_1000"] = static_cast<double>(bytes_at_1000) / 1000.0;
    state.counters["bytes_per_trial_last_1000"] = static_cast<double>(bytes_end - bytes_before_last_1000) / 1000.0;
    state.counters["database_MB"] = static_cast<double>(bytes_end) / 1e6;
    state.counters["schema2_state_bytes_last_row"] = static_cast<double>(tracks_state(tracks).dump().size());
    state.counters["commit_us_per_trial"] = commit_s / trials * 1e6;
  }
  fs::remove_all(dir);
}
BENCHMARK(ThresholdStoreGrowth)->Arg(20000)->Iterations(1)->Unit(benchmark::kSecond);

void PlanLongSession(benchmark::State& state) {
  const std::vector<int> counts(8, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    RandomSource random(42);
    std::vector<int> order;
    if (!extend_constrained_order(order, counts, OrderConstraints{1, 0}, random)) state.SkipWithError("infeasible");
    benchmark::DoNotOptimize(order.data());
  }
  state.counters["trials"] = 8.0 * static_cast<double>(state.range(0));
}
BENCHMARK(PlanLongSession)->Arg(1000)->Arg(2500)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
