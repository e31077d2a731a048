#include "study/training.hpp"

#include <algorithm>
#include <cstdio>

#include "study/localisation_case.hpp"
#include "study/random_source.hpp"

namespace palprig {

namespace {

std::string fixed2(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  return buf;
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

double number_or_nan(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : std::numeric_limits<double>::quiet_NaN();
}

const char* feedback_word(Feedback f) {
  return f == Feedback::none ? "none" : f == Feedback::practice ? "practice" : "all";
}

std::string pulse_case_key(CaseDifficulty d, std::uint64_t seed) {
  return std::string("pulse:") + to_string(d) + ":" + std::to_string(seed);
}

}  // namespace

CaseResult case_result(const TrialRecord& t) {
  CaseResult c;
  c.name = t.case_name;
  c.answered = t.answered;
  c.tumors = t.case_tumors;
  if (t.answered) {
    for (const TumorScore& s : t.localisation.tumors) c.found += s.hit ? 1 : 0;
    c.false_marks = t.localisation.false_marks;
    c.time_s = t.response_time_s;
  }
  return c;
}

CaseResult case_result(const PulseTrialRecord& t) {
  CaseResult c;
  c.name = t.condition;
  c.pulse = true;
  c.answered = t.answered;
  c.tumors = 1;
  if (t.answered) {
    c.found = t.hit ? 1 : 0;
    c.time_s = t.response_time_s;
    c.distance_mm = t.distance_mm;
  }
  return c;
}

int SessionScores::targets() const {
  int n = 0;
  for (const auto& c : cases) n += c.tumors;
  return n;
}
int SessionScores::found() const {
  int n = 0;
  for (const auto& c : cases) n += c.found;
  return n;
}
int SessionScores::normal_cases() const {
  return static_cast<int>(std::count_if(cases.begin(), cases.end(), [](const CaseResult& c) { return c.normal(); }));
}
int SessionScores::normal_called() const {
  return static_cast<int>(std::count_if(
      cases.begin(), cases.end(), [](const CaseResult& c) { return c.normal() && c.answered && c.false_marks == 0; }));
}
int SessionScores::false_marks() const {
  int n = 0;
  for (const auto& c : cases) n += c.false_marks;
  return n;
}
std::optional<double> SessionScores::found_fraction() const {
  if (targets() == 0) return std::nullopt;
  return static_cast<double>(found()) / targets();
}
std::optional<double> SessionScores::false_marks_per_case() const {
  if (cases.empty()) return std::nullopt;
  return static_cast<double>(false_marks()) / static_cast<double>(cases.size());
}
std::optional<double> SessionScores::time_per_case_s() const {
  double sum = 0;
  int n = 0;
  for (const auto& c : cases) {
    if (c.answered && std::isfinite(c.time_s)) {
      sum += c.time_s;
      ++n;
    }
  }
  if (n == 0) return std::nullopt;
  return sum / n;
}
std::optional<double> SessionScores::normal_called_fraction() const {
  if (normal_cases() == 0) return std::nullopt;
  return static_cast<double>(normal_called()) / normal_cases();
}

nlohmann::json to_json(const SessionScores& s) {
  nlohmann::json cases = nlohmann::json::array();
  for (const CaseResult& c : s.cases) {
    cases.push_back({{"name", c.name},
                     {"pulse", c.pulse},
                     {"answered", c.answered},
                     {"tumors", c.tumors},
                     {"found", c.found},
                     {"false_marks", c.false_marks},
                     {"time_s", number_or_null(c.time_s)},
                     {"distance_mm", number_or_null(c.distance_mm)}});
  }
  return {{"cases", cases}};
}

SessionScores scores_from_json(const nlohmann::json& j) {
  SessionScores s;
  if (!j.is_object() || !j.contains("cases") || !j["cases"].is_array()) return s;
  for (const auto& o : j["cases"]) {
    if (!o.is_object()) continue;
    CaseResult c;
    c.name = o.value("name", std::string());
    c.pulse = o.value("pulse", false);
    c.answered = o.value("answered", false);
    c.tumors = o.value("tumors", 0);
    c.found = o.value("found", 0);
    c.false_marks = o.value("false_marks", 0);
    c.time_s = number_or_nan(o, "time_s");
    c.distance_mm = number_or_nan(o, "distance_mm");
    s.cases.push_back(c);
  }
  return s;
}

BenchmarkResult check_benchmark(const LevelBenchmark& b, const SessionScores& s) {
  BenchmarkResult r;
  const auto shortfall = [&](const std::string& what, std::optional<double> got, const char* relation, double wanted) {
    r.shortfalls.push_back(what + " " + (got ? fixed2(*got) : std::string("n/a")) + " (wanted " + relation + " " +
                           fixed2(wanted) + ")");
  };
  if (b.found_min) {
    const auto got = s.found_fraction();
    if (!got || *got < *b.found_min)
      shortfall(s.cases.empty() || !s.cases[0].pulse ? "tumors found" : "pulses found", got, ">=", *b.found_min);
  }
  if (b.false_marks_per_case_max) {
    const auto got = s.false_marks_per_case();
    if (!got || *got > *b.false_marks_per_case_max)
      shortfall("false marks per case", got, "<=", *b.false_marks_per_case_max);
  }
  if (b.time_per_case_max_s) {
    const auto got = s.time_per_case_s();
    if (!got || *got > *b.time_per_case_max_s) shortfall("seconds per case", got, "<=", *b.time_per_case_max_s);
  }
  if (b.normal_called_min) {
    // A session without a normal case has nothing to show here: not held against it.
    const auto got = s.normal_called_fraction();
    if (got && *got < *b.normal_called_min) shortfall("normal cases called normal", got, ">=", *b.normal_called_min);
  }
  r.met = r.shortfalls.empty();
  return r;
}

bool case_failed(const CaseResult& c, const LevelBenchmark& b) {
  if (!c.answered) return true;
  const int allowance = b.false_marks_per_case_max ? static_cast<int>(std::floor(*b.false_marks_per_case_max)) : 0;
  if (c.normal()) return c.false_marks > 0;
  return c.found < c.tumors || c.false_marks > allowance;
}

TrainingStanding training_standing(const Curriculum& curriculum, const std::vector<TrainingSessionRecord>& history) {
  TrainingStanding st;
  const int levels = static_cast<int>(curriculum.levels.size());
  for (const TrainingSessionRecord& r : history) {
    if (r.curriculum != curriculum.name) continue;
    if (!r.completed()) {
      st.running_session = r.session_id;
      continue;
    }
    ++st.sessions;
    if (st.level >= levels) continue;
    // Matched by name: a level the curriculum no longer has (or a session run at another level
    // on purpose) does not move the trainee.
    if (r.level_name != curriculum.levels[static_cast<std::size_t>(st.level)].name) continue;
    ++st.sessions_at_level;
    st.consecutive_met = r.met_benchmark.value_or(false) ? st.consecutive_met + 1 : 0;
    if (st.consecutive_met >= curriculum.levels[static_cast<std::size_t>(st.level)].benchmark.consecutive_sessions) {
      st.passed_after.push_back(st.sessions);
      ++st.level;
      st.sessions_at_level = 0;
      st.consecutive_met = 0;
    }
  }
  st.finished = st.level >= levels;
  return st;
}

std::string training_protocol_name(const Curriculum& curriculum, int level) {
  return curriculum.name + " / " + curriculum.levels.at(static_cast<std::size_t>(level)).name;
}

PlannedTrainingSession plan_training_session(const Curriculum& curriculum, int level_index, const std::string& trainee,
                                             const std::set<std::string>& given, int session_number) {
  const CurriculumLevel& level = curriculum.levels.at(static_cast<std::size_t>(level_index));
  PlannedTrainingSession plan;
  plan.level = level_index;
  plan.pulse = level.cases == LevelCases::generated_pulse;
  plan.protocol_name = training_protocol_name(curriculum, level_index);
  std::set<std::string> taken = given;
  if (level.cases == LevelCases::scene_set) {
    // Scenes not given yet first, in the listed order; then the set again from its start.
    std::vector<TrainingCase> fresh, seen;
    for (const auto& file : level.scenes) {
      const LocalisationCase c = file_localisation_case(file);
      (given.count(case_key(c)) ? seen : fresh).push_back({case_key(c), c.name, std::nullopt, file});
    }
    fresh.insert(fresh.end(), seen.begin(), seen.end());
    // A session never shows a scene twice: a set smaller than a session is the whole session.
    const std::size_t n = std::min(fresh.size(), static_cast<std::size_t>(level.cases_per_session));
    plan.cases.assign(fresh.begin(), fresh.begin() + static_cast<std::ptrdiff_t>(n));
  } else {
    RandomSource random(
        stable_hash(trainee + '\n' + curriculum.name + '\n' + level.name + '\n' + std::to_string(session_number)));
    while (static_cast<int>(plan.cases.size()) < level.cases_per_session) {
      const std::uint64_t seed = random.below(1000000000ULL);  // a seed a person can type again
      const std::string key =
          plan.pulse ? pulse_case_key(level.difficulty, seed) : generated_case_key(level.difficulty, seed);
      if (!taken.insert(key).second) continue;  // never the same case twice
      const std::string name =
          std::string(plan.pulse ? "pulse-" : "case-") + to_string(level.difficulty) + "-" + std::to_string(seed);
      plan.cases.push_back({key, name, seed, {}});
    }
  }

  const std::string description = "Training: " + curriculum.name + ", level '" + level.name + "' (" +
                                  std::to_string(plan.cases.size()) + " cases).";
  nlohmann::json& p = plan.protocol;
  p = {{"version", 1}, {"name", plan.protocol_name}, {"description", description}, {"repetitions", 1}};
  if (plan.pulse) {
    p["task"] = "pulse";
    p["pulse"] = {{"hit_radius_mm", curriculum.tolerance_mm},
                  {"max_present_s", level.time_limit_s},
                  {"response_timeout_s", 5.0},
                  {"inter_trial_s", 2.0}};
    nlohmann::json conditions = nlohmann::json::array();
    for (const TrainingCase& c : plan.cases) {
      conditions.push_back(
          {{"name", c.name}, {"generate", {{"difficulty", to_string(level.difficulty)}, {"seed", *c.seed}}}});
    }
    p["conditions"] = conditions;
  } else {
    nlohmann::json cases = nlohmann::json::array();
    for (const TrainingCase& c : plan.cases) {
      if (c.seed)
        cases.push_back({{"difficulty", to_string(level.difficulty)}, {"seed", *c.seed}});
      else
        cases.push_back(std::filesystem::absolute(c.scene_file).string());
    }
    p["task"] = "localisation";
    p["localisation"] = {{"cases", cases}, {"tolerance_mm", curriculum.tolerance_mm}};
    p["conditions"] = nlohmann::json::array({{{"name", level.name}, {"mode", "scene"}}});
    p["repetitions"] = 1;
    p["randomisation"] = {{"scheme", "fixed"}};
    p["timing"] = {{"max_present_s", level.time_limit_s}, {"response_timeout_s", 5.0}, {"inter_trial_s", 2.0}};
    p["feedback"] = feedback_word(level.feedback);  // pulse protocols tell nothing (they have no feedback)
  }
  return plan;
}

double pilot_skill(const CurriculumPilot& pilot, int cases_practised) {
  const double n = std::max(0, cases_practised);
  return 1.0 - (1.0 - pilot.initial_skill) * std::exp(-pilot.learning_rate_per_case * n);
}

std::vector<std::optional<int>> predict_pilot_sessions(const Curriculum& curriculum, int max_sessions,
                                                       const std::vector<double>& expert_found) {
  std::vector<std::optional<int>> first(curriculum.levels.size());
  if (first.empty()) return first;
  first[0] = 1;
  int level = 0, run = 0, practised = 0;
  for (int session = 1; session <= max_sessions && level < static_cast<int>(curriculum.levels.size()); ++session) {
    const CurriculumLevel& l = curriculum.levels[static_cast<std::size_t>(level)];
    double expected = 0;
    for (int i = 0; i < l.cases_per_session; ++i) expected += pilot_skill(curriculum.pilot, practised + i);
    expected /= l.cases_per_session;
    if (static_cast<std::size_t>(level) < expert_found.size())
      expected *= expert_found[static_cast<std::size_t>(level)];
    practised += l.cases_per_session;
    const bool met = !l.benchmark.found_min || expected >= *l.benchmark.found_min;
    run = met ? run + 1 : 0;
    if (run >= l.benchmark.consecutive_sessions) {
      ++level;
      run = 0;
      if (level < static_cast<int>(first.size())) first[static_cast<std::size_t>(level)] = session + 1;
    }
  }
  return first;
}

}  // namespace palprig
