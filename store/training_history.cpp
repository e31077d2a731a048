#include "store/training_history.hpp"

// Trainees, standings, curves and expert benchmarks from a store (store/training_history.hpp).
#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>

#include "core/input_error.hpp"
#include "statistics/statistics_describe.hpp"
#include "store/pg_target.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/pulse_store.hpp"
#include "store/sqlite_trial_store.hpp"

namespace palprig {

namespace {

CaseResult stored_case_result(const StoredTrial& t) {
  CaseResult c;
  c.name = t.case_name.value_or("");
  c.answered = t.answered;
  c.tumors = t.case_tumors.value_or(static_cast<int>(t.tumor_outcomes.size()));
  if (t.answered) {
    for (const auto& [tumor, outcome] : t.tumor_outcomes) c.found += outcome == "TP" ? 1 : 0;
    c.false_marks = static_cast<int>(t.false_marks.value_or(0));
    c.time_s = t.response_time_s.value_or(std::numeric_limits<double>::quiet_NaN());
  }
  return c;
}

}  // namespace

std::unique_ptr<TrialStore> open_training_store(const std::string& location, TrialStore::Access access) {
  // A lab server directly (enrolments, history and the cases given are the server's, so every
  // rig sees them); the session itself writes its trials through the bench journal as always.
  if (is_server_store_location(location))
    return std::make_unique<PostgresTrialStore>(parse_pg_target(location), access);
  if (access == TrialStore::Access::read_only) return open_trial_store(location, access);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(location, ec)) {
    throw InputError(location, "file",
                     "an existing trial database with enrolled trainees (enrol one first: palprig train enrol)");
  }
  return std::make_unique<SqliteTrialStore>(location, access);
}

void require_enrolled(TrialStore& store, const Curriculum& curriculum, const std::string& trainee) {
  if (trainee.empty()) throw InputError("command line", "trainee", "a trainee code");
  for (const TraineeRecord& t : store.trainees()) {
    if (t.code == trainee && t.curriculum == curriculum.name) return;
  }
  throw InputError(store.location(), "trainee '" + trainee + "'",
                   "a trainee enrolled in curriculum '" + curriculum.name +
                       "' (none is by that code; enrol them with: palprig train enrol)");
}

std::vector<TrainingSessionRecord> of_curriculum(const std::vector<TrainingSessionRecord>& history,
                                                 const std::string& curriculum) {
  std::vector<TrainingSessionRecord> out;
  for (const auto& r : history) {
    if (r.curriculum == curriculum) out.push_back(r);
  }
  return out;
}

// A session's cases as committed, before position `before` (all: -1).
std::vector<CaseResult> stored_cases(TrialStore& store, std::int64_t session_id, bool pulse, int before) {
  std::vector<CaseResult> out;
  if (pulse) {
    auto* sqlite = dynamic_cast<SqliteTrialStore*>(&store);
    if (!sqlite) return out;
    PulseStore pulses(*sqlite, false);
    for (const PulseTrialRecord& t : pulses.read_trials(session_id)) {
      if (before < 0 || t.position < before) out.push_back(case_result(t));
    }
    return out;
  }
  for (const StoredTrial& t : store.read_session_trials(session_id)) {
    if (before < 0 || t.position < before) out.push_back(stored_case_result(t));
  }
  return out;
}

const CurriculumLevel* level_named(const Curriculum& c, const std::string& name) {
  for (const auto& l : c.levels) {
    if (l.name == name) return &l;
  }
  return nullptr;
}

// A training row left running by a process that ended after its session completed: scored now
// from the stored trials.
void complete_left_behind(TrialStore& store, const Curriculum& curriculum,
                          std::vector<TrainingSessionRecord>& history) {
  std::map<std::int64_t, std::string> status;
  for (const SessionOverview& s : store.list_sessions()) status[s.id] = s.status;
  for (TrainingSessionRecord& r : history) {
    if (r.completed() || r.curriculum != curriculum.name || status[r.session_id] != "completed") continue;
    const CurriculumLevel* level = level_named(curriculum, r.level_name);
    SessionScores scores;
    scores.cases = stored_cases(store, r.session_id, level && level->cases == LevelCases::generated_pulse, -1);
    const bool met = level && check_benchmark(level->benchmark, scores).met;
    store.complete_training_session(r.session_id, to_json(scores), met);
    r.status = "completed";
    r.scores = to_json(scores);
    r.met_benchmark = met;
  }
}

void enrol_trainee(const std::string& store_location, const Curriculum& curriculum, const std::string& trainee) {
  if (trainee.empty()) throw InputError("command line", "trainee", "a trainee code");
  if (trainee.rfind("sim:", 0) == 0) {
    throw InputError("command line", "trainee",
                     "a trainee's own code (a simulated pilot trainee is any code run with --participant sim:SEED), "
                     "got '" +
                         trainee + "'");
  }
  const auto store = is_server_store_location(store_location)
                         ? std::unique_ptr<TrialStore>(std::make_unique<PostgresTrialStore>(
                               parse_pg_target(store_location), TrialStore::Access::read_write))
                         : open_trial_store(store_location, TrialStore::Access::read_write);
  store->enrol_trainee(trainee, curriculum.name);
}

TraineeStanding trainee_standing(const std::string& store_location, const Curriculum& curriculum,
                                 const std::string& trainee) {
  const auto store = open_training_store(store_location, TrialStore::Access::read_only);
  require_enrolled(*store, curriculum, trainee);
  TraineeStanding out;
  out.trainee = trainee;
  out.sessions = of_curriculum(store->training_sessions(trainee), curriculum.name);
  out.standing = training_standing(curriculum, out.sessions);
  for (const auto& r : out.sessions) out.scores.push_back(r.completed() ? scores_from_json(r.scores) : SessionScores{});
  return out;
}

std::vector<TraineeStanding> curriculum_standings(const std::string& store_location, const Curriculum& curriculum) {
  const auto store = open_training_store(store_location, TrialStore::Access::read_only);
  std::vector<TraineeStanding> out;
  for (const TraineeRecord& t : store->trainees()) {
    if (t.curriculum != curriculum.name) continue;
    TraineeStanding s;
    s.trainee = t.code;
    s.sessions = of_curriculum(store->training_sessions(t.code), curriculum.name);
    s.standing = training_standing(curriculum, s.sessions);
    for (const auto& r : s.sessions) s.scores.push_back(r.completed() ? scores_from_json(r.scores) : SessionScores{});
    out.push_back(std::move(s));
  }
  return out;
}

TrainingCurves training_curves(const Curriculum& curriculum, const TraineeStanding& trainee) {
  TrainingCurves c;
  std::vector<std::pair<std::int64_t, std::int64_t>> found, normal;
  std::vector<std::vector<double>> false_marks, times;
  for (std::size_t i = 0; i < trainee.sessions.size(); ++i) {
    const TrainingSessionRecord& r = trainee.sessions[i];
    if (!r.completed()) continue;
    const SessionScores& s = trainee.scores[i];
    const CurriculumLevel* level = level_named(curriculum, r.level_name);
    const LevelBenchmark benchmark = level ? level->benchmark : LevelBenchmark{};
    c.level.push_back(level ? static_cast<int>(level - curriculum.levels.data()) : r.level);
    found.emplace_back(s.found(), s.targets());
    normal.emplace_back(s.normal_called(), s.normal_cases());
    std::vector<double> marks, time;
    for (const CaseResult& k : s.cases) {
      marks.push_back(k.false_marks);
      if (k.answered && std::isfinite(k.time_s)) time.push_back(k.time_s);
      c.case_failures.push_back(case_failed(k, benchmark));
    }
    false_marks.push_back(marks);
    times.push_back(time);
    c.found_min.push_back(benchmark.found_min);
    c.false_marks_max.push_back(benchmark.false_marks_per_case_max);
    c.time_max_s.push_back(benchmark.time_per_case_max_s);
    c.normal_called_min.push_back(benchmark.normal_called_min);
    c.met.push_back(r.met_benchmark.value_or(false));
  }
  c.found = stats::proportion_curve(found);
  c.normal_called = stats::proportion_curve(normal);
  c.false_marks = stats::mean_curve(false_marks);
  c.time_per_case = stats::mean_curve(times);
  const stats::CusumRates rates{curriculum.cusum.acceptable_failure_rate, curriculum.cusum.unacceptable_failure_rate};
  const stats::CusumErrors errors{curriculum.cusum.alpha, curriculum.cusum.beta, curriculum.cusum.horizon_cases};
  c.cusum_limit = stats::cusum_limit(stats::CusumChart::monitoring, rates, errors);
  c.lc_cusum_limit = stats::cusum_limit(stats::CusumChart::learning, rates, errors);
  c.cusum = stats::cusum_series(stats::CusumChart::monitoring, rates, c.cusum_limit.limit, c.case_failures);
  c.lc_cusum = stats::cusum_series(stats::CusumChart::learning, rates, c.lc_cusum_limit.limit, c.case_failures);
  return c;
}

ExpertBenchmark expert_benchmark(const std::string& store_location, const Curriculum& curriculum, int level,
                                 const std::vector<std::string>& experts, std::optional<double> percentile) {
  const auto store = open_training_store(store_location, TrialStore::Access::read_only);
  const CurriculumLevel& l = curriculum.levels.at(static_cast<std::size_t>(level));
  ExpertBenchmark out;
  out.level = level;
  out.experts = experts;
  std::vector<double> found, false_marks, times, normal;
  for (const std::string& expert : experts) {
    for (const TrainingSessionRecord& r : store->training_sessions(expert)) {
      if (r.curriculum != curriculum.name || r.level_name != l.name || !r.completed()) continue;
      const SessionScores s = scores_from_json(r.scores);
      ++out.sessions;
      if (auto v = s.found_fraction()) found.push_back(*v);
      if (auto v = s.false_marks_per_case()) false_marks.push_back(*v);
      if (auto v = s.time_per_case_s()) times.push_back(*v);
      if (auto v = s.normal_called_fraction()) normal.push_back(*v);
    }
  }
  if (out.sessions == 0) {
    std::string names;
    for (const auto& e : experts) names += (names.empty() ? "" : ", ") + e;
    throw InputError(store->location(), "experts",
                     "experts with a completed session at level '" + l.name + "' of '" + curriculum.name + "' (" +
                         (names.empty() ? std::string("none named") : names + " have none") +
                         "; run it with: palprig train next --level '" + l.name + "')");
  }
  // Higher-is-better measures at the percentile from the bottom, lower-is-better from the top.
  const auto pick = [&](std::vector<double> v, bool higher_better) -> std::optional<double> {
    if (v.empty()) return std::nullopt;
    std::sort(v.begin(), v.end());
    if (!percentile) {
      double sum = 0;
      for (double x : v) sum += x;
      return sum / static_cast<double>(v.size());
    }
    const double p = *percentile / 100.0;
    return stats::quantile_sorted(v, higher_better ? p : 1.0 - p);
  };
  out.benchmark.consecutive_sessions = l.benchmark.consecutive_sessions;
  out.benchmark.found_min = pick(found, true);
  out.benchmark.false_marks_per_case_max = pick(false_marks, false);
  out.benchmark.time_per_case_max_s = pick(times, false);
  out.benchmark.normal_called_min = pick(normal, true);
  return out;
}

}  // namespace palprig
