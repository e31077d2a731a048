// The lab store: trial commit latency p50/p99 to the bench's journal (SQLite, WAL,
// synchronous FULL) and to the PostgreSQL server on loopback, and `stats trials` over a million
// trials read from PostgreSQL, beside the same scan of the SQLite file.
//
// Needs a server: run through bench/lab_store.sh (pg_virtualenv with fsync on, so a server
// commit reaches the disk as a real lab server's does). The million trials come from
// bench_stats' file $TMPDIR/palprig_bench_1M_trials.db (run bench_stats once first) and are
// copied into the server with `palprig store copy`'s engine; the copy time is reported.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "study/protocol.hpp"
#include "study/scoring.hpp"
#include "study/session_plan.hpp"
#include "store/journaled_trial_store.hpp"
#include "store/lab_sync.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_summary.hpp"

namespace {

using namespace palprig;

std::string server_uri(const std::string& dbname) {
  const char* user = std::getenv("PGUSER");
  const char* host = std::getenv("PGHOST");
  const char* port = std::getenv("PGPORT");
  return std::string("postgresql://") + (user ? user : "postgres") + "@" + (host ? host : "localhost") + ":" +
         (port ? port : "5432") + "/" + dbname;
}

bool have_server() { return std::getenv("PGPORT") != nullptr; }

void create_database(const std::string& name) {
  PgConnection admin(parse_pg_target(server_uri("postgres")));
  admin.exec("DROP DATABASE IF EXISTS " + name);
  admin.exec("CREATE DATABASE " + name);
}

Protocol protocol() {
  return load_protocol(std::filesystem::path(PALPRIG_SOURCE_DIR) / "data" / "protocols" / "discrimination_002.json");
}

TrialRecord trial_at(const Protocol& p, int position) {
  TrialRecord r;
  const auto& c = p.combinations[static_cast<std::size_t>(position) % p.combinations.size()];
  r.planned = PlannedTrial{position, 0, 0, false, 0, false};
  r.condition = p.conditions[0].name;
  r.mode = p.conditions[0].mode;
  r.combination_label = c.label;
  r.stimulus_kPa = c.pressure_kPa;
  r.felt_kPa = c.pressure_kPa;
  r.truth = c.tumor;
  r.answer = c.tumor;
  r.answered = true;
  r.finger_outcomes = score_discrimination(r.truth, r.answer);
  r.onset_s = 10.0 * position;
  r.response_time_s = 4.6;
  return r;
}

// Each iteration commits one trial; the latencies give p50 and p99 (microseconds).
void commit_latency(benchmark::State& state, TrialStore& store) {
  const Protocol p = protocol();
  const ParticipantRecord who = store.enrol("bench:" + std::to_string(std::rand()), true);
  const SessionPlan plan = make_session_plan(p, who.number, 7);
  const std::int64_t session =
      store.create_session(who, p, plan, SessionSetup{"bench", "simulated", "paper002", nullptr, "."});
  std::vector<double> us;
  int position = 0;
  for (auto _ : state) {
    const TrialRecord r = trial_at(p, position++);
    const auto t0 = std::chrono::steady_clock::now();
    store.commit_trial(session, r);
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(us.begin(), us.end());
  state.counters["p50_us"] = us[us.size() / 2];
  state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
}

void BM_CommitTrial_Journal(benchmark::State& state) {
  if (!have_server()) return state.SkipWithError("no PostgreSQL server: run through bench/lab_store.sh");
  create_database("bench_journal");
  const auto journal = std::filesystem::temp_directory_path() / "palprig_bench_journal.db";
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(journal.string() + suffix);
  // The session's path: commit to the journal (fsync'd), the pusher sends it on its own thread.
  JournaledTrialStore store(parse_pg_target(server_uri("bench_journal")), journal, [](const std::string&) {});
  commit_latency(state, store);
  state.counters["pending_after_flush"] = static_cast<double>(store.flush(std::chrono::seconds(60)));
}
BENCHMARK(BM_CommitTrial_Journal)->Unit(benchmark::kMicrosecond)->Iterations(2000);

void BM_CommitTrial_Server(benchmark::State& state) {
  if (!have_server()) return state.SkipWithError("no PostgreSQL server: run through bench/lab_store.sh");
  create_database("bench_server");
  PostgresTrialStore store(parse_pg_target(server_uri("bench_server")), TrialStore::Access::read_write);
  state.SetLabel("fsync=" + store.connection().exec("SHOW fsync").text(0, 0) +
                 " synchronous_commit=" + store.connection().exec("SHOW synchronous_commit").text(0, 0));
  commit_latency(state, store);
}
BENCHMARK(BM_CommitTrial_Server)->Unit(benchmark::kMicrosecond)->Iterations(2000);

std::filesystem::path million_file() { return std::filesystem::temp_directory_path() / "palprig_bench_1M_trials.db"; }

void summarise(benchmark::State& state, TrialStore& store) {
  SummaryOptions options;
  options.by = parse_summary_keys("condition");
  std::size_t trials = 0;
  for (auto _ : state) {
    const TrialSummary summary = summarise_trials(store, options);
    trials = 0;
    for (const SummaryRow& row : summary.rows) trials += static_cast<std::size_t>(row.trials);
    benchmark::DoNotOptimize(summary.rows.data());
  }
  state.counters["trials"] = static_cast<double>(trials);
}

void BM_StatsTrials_1M_Sqlite(benchmark::State& state) {
  if (!std::filesystem::exists(million_file()))
    return state.SkipWithError("run bench_stats first (it builds the file)");
  SqliteTrialStore store(million_file(), TrialStore::Access::read_only);
  summarise(state, store);
}
BENCHMARK(BM_StatsTrials_1M_Sqlite)->Unit(benchmark::kMillisecond)->MinTime(3.0);

void BM_StatsTrials_1M_Postgres(benchmark::State& state) {
  if (!have_server()) return state.SkipWithError("no PostgreSQL server: run through bench/lab_store.sh");
  if (!std::filesystem::exists(million_file()))
    return state.SkipWithError("run bench_stats first (it builds the file)");
  static double copy_s = [] {
    create_database("bench_million");
    const auto t0 = std::chrono::steady_clock::now();
    copy_study(million_file().string(), server_uri("bench_million"), std::nullopt);
    PgConnection(parse_pg_target(server_uri("bench_million"))).exec("VACUUM ANALYZE");
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }();
  PostgresTrialStore store(parse_pg_target(server_uri("bench_million")), TrialStore::Access::read_only);
  state.counters["copy_in_s"] = copy_s;
  summarise(state, store);
}
BENCHMARK(BM_StatsTrials_1M_Postgres)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
