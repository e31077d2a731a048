// `palprig stats trials` on a million trials (goal: under 1 s), and the rank-test and
// Wilson kernels. The trial database is built once (about a minute) in the temporary folder and
// reused: $TMPDIR/palprig_bench_1M_trials.db (delete it to rebuild).
//
// Trials: 1000 simulated participants x 1000 discrimination trials (two conditions, 14
// combinations of paper 002, per-finger outcomes drawn with 95 % accuracy).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <vector>

#include "study/protocol.hpp"
#include "study/random_source.hpp"
#include "study/session_plan.hpp"
#include "statistics/statistics_proportion.hpp"
#include "statistics/statistics_rank_tests.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_summary.hpp"
#include "store/trial_summary_report.hpp"

namespace {

using namespace palprig;

constexpr int kParticipants = 1000;
constexpr int kTrialsPerParticipant = 1000;

std::filesystem::path bench_db() { return std::filesystem::temp_directory_path() / "palprig_bench_1M_trials.db"; }

bool has_all_trials(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) return false;
  try {
    SqliteTrialStore store(file, TrialStore::Access::read_only);
    auto q = store.database().prepare("SELECT count(*) FROM trials");
    return q.step() && q.integer(0) == static_cast<std::int64_t>(kParticipants) * kTrialsPerParticipant;
  } catch (const std::exception&) {
    return false;
  }
}

void build_db(const std::filesystem::path& file) {
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(file.string() + suffix);
  const Protocol p =
      load_protocol(std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "protocols" / "discrimination_002.json");
  SqliteTrialStore store(file, TrialStore::Access::read_write);
  RandomSource random(2024);
  for (int who = 0; who < kParticipants; ++who) {
    const ParticipantRecord participant = store.enrol("sim:" + std::to_string(who), true);
    const SessionPlan plan = make_session_plan(p, participant.number, static_cast<std::uint64_t>(who));
    const std::int64_t session =
        store.create_session(participant, p, plan, SessionSetup{"bench", "simulated", "paper002", nullptr, "."});
    std::vector<TrialRecord> trials(kTrialsPerParticipant);
    for (int i = 0; i < kTrialsPerParticipant; ++i) {
      TrialRecord& r = trials[static_cast<std::size_t>(i)];
      const int condition = i < kTrialsPerParticipant / 2 ? 0 : 1;
      const auto& c = p.combinations[random.below(p.combinations.size())];
      r.planned = PlannedTrial{i, condition, condition, false, 0, false};
      r.condition = p.conditions[static_cast<std::size_t>(condition)].name;
      r.mode = p.conditions[static_cast<std::size_t>(condition)].mode;
      r.combination_label = c.label;
      r.stimulus_kPa = c.pressure_kPa;
      r.felt_kPa = c.pressure_kPa;
      r.truth = c.tumor;
      r.answered = true;
      for (std::size_t f = 0; f < kFingerCount; ++f) r.answer[f] = random.uniform() < 0.95 ? c.tumor[f] : !c.tumor[f];
      r.finger_outcomes = score_discrimination(r.truth, r.answer);
      r.onset_s = 10.0 * i;
      r.response_time_s = random.lognormal_with_mean_sd(condition == 0 ? 4.6 : 8.3, condition == 0 ? 2.3 : 2.9);
    }
    store.commit_trials(session, trials);
  }
}

TrialStore& store() {
  static const bool ready = [] {
    if (!has_all_trials(bench_db())) build_db(bench_db());
    return true;
  }();
  (void)ready;
  static SqliteTrialStore s(bench_db(), TrialStore::Access::read_only);
  return s;
}

void run_summary(benchmark::State& state, const std::string& by) {
  TrialStore& s = store();
  SummaryOptions options;
  options.by = parse_summary_keys(by);
  std::size_t rows = 0;
  for (auto _ : state) {
    const TrialSummary summary = summarise_trials(s, options);
    const std::string table = summary_table(summary);
    benchmark::DoNotOptimize(table.data());
    rows = summary.rows.size();
  }
  state.counters["groups"] = static_cast<double>(rows);
  state.counters["trials/s"] = benchmark::Counter(static_cast<double>(kParticipants) * kTrialsPerParticipant,
                                                  benchmark::Counter::kIsIterationInvariantRate);
}

void BM_StatsTrials_1M_ByCondition(benchmark::State& state) { run_summary(state, "condition"); }
void BM_StatsTrials_1M_ByConditionParticipantFinger(benchmark::State& state) {
  run_summary(state, "condition,participant,finger");
}
BENCHMARK(BM_StatsTrials_1M_ByCondition)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_StatsTrials_1M_ByConditionParticipantFinger)->Unit(benchmark::kMillisecond)->MinTime(3.0);

void BM_MannWhitneyExact_49x49(benchmark::State& state) {
  std::vector<double> a, b;
  for (int i = 0; i < 49; ++i) {
    a.push_back(2.0 * i);
    b.push_back(2.0 * i + 1.0);
  }
  for (auto _ : state) benchmark::DoNotOptimize(stats::mann_whitney(a, b).p);
}
BENCHMARK(BM_MannWhitneyExact_49x49)->Unit(benchmark::kMicrosecond);

void BM_Wilson(benchmark::State& state) {
  std::int64_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(stats::wilson_interval(k++ % 505, 504).lower);
}
BENCHMARK(BM_Wilson);

}  // namespace

BENCHMARK_MAIN();
