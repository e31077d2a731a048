#include "study/curriculum.hpp"

#include <set>

#include "formats/json_file.hpp"
#include "formats/scene_file.hpp"
#include "core/input_error.hpp"

namespace palprig {

namespace {

constexpr int kMaxCasesPerSession = 200;
constexpr int kMaxLevels = 100;

Feedback read_feedback(const JsonObject& o) {
  const std::string word = o.choice_or("feedback", "all", {"none", "practice", "all"});
  return word == "none" ? Feedback::none : word == "practice" ? Feedback::practice : Feedback::all;
}

CaseDifficulty read_difficulty(const JsonObject& o, const std::string& key) {
  return parse_difficulty(o.choice(key, {"easy", "medium", "hard"}));
}

void read_cases(const JsonObject& level, const std::filesystem::path& base_dir, CurriculumLevel& out) {
  const JsonObject cases = level.object("cases");
  const int given = (cases.has("generate") ? 1 : 0) + (cases.has("pulse") ? 1 : 0) + (cases.has("scenes") ? 1 : 0);
  if (given != 1) {
    cases.fail("generate",
               "exactly one of `generate` (a difficulty: generated tumor cases), `pulse` (a difficulty: generated "
               "pulse cases) or `scenes` (a list of scene files)");
  }
  if (cases.has("generate")) {
    out.cases = LevelCases::generated_tumors;
    out.difficulty = read_difficulty(cases, "generate");
  } else if (cases.has("pulse")) {
    out.cases = LevelCases::generated_pulse;
    out.difficulty = read_difficulty(cases, "pulse");
  } else {
    out.cases = LevelCases::scene_set;
    const auto& list = cases.raw("scenes");
    const std::string where = cases.path("scenes");
    if (!list.is_array() || list.empty())
      throw InputError(cases.file(), where, "a non-empty array of scene file names");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = where + "[" + std::to_string(i) + "]";
      if (!list[i].is_string() || list[i].get<std::string>().empty())
        throw InputError(cases.file(), at, "a scene file name, got " + json_excerpt(list[i]));
      const std::filesystem::path p = list[i].get<std::string>();
      const std::filesystem::path file = p.is_absolute() ? p : base_dir / p;
      // Loaded now, so a missing or bad scene is refused with the curriculum, not at a session.
      try {
        (void)load_scene_file(file);
      } catch (const InputError& e) {
        throw InputError(cases.file(), at, std::string("a scene file palprig reads (") + e.what() + ")");
      }
      out.scenes.push_back(file);
    }
  }
  cases.refuse_unknown();
}

LevelBenchmark read_benchmark(const JsonObject& level) {
  LevelBenchmark b;
  if (!level.has("benchmark")) return b;
  const JsonObject o = level.object("benchmark");
  if (o.has("found_min")) b.found_min = o.number("found_min", 0.0, 1.0);
  if (o.has("false_marks_per_case_max")) b.false_marks_per_case_max = o.number("false_marks_per_case_max", 0.0, 1000.0);
  if (o.has("time_per_case_max_s")) b.time_per_case_max_s = o.number("time_per_case_max_s", 0.1, 36000.0);
  if (o.has("normal_called_min")) b.normal_called_min = o.number("normal_called_min", 0.0, 1.0);
  b.consecutive_sessions = static_cast<int>(o.integer_or("consecutive_sessions", 2, 1, 100));
  o.refuse_unknown();
  if (!b.found_min && !b.false_marks_per_case_max && !b.time_per_case_max_s && !b.normal_called_min) {
    o.fail("found_min",
           "at least one measure to meet (found_min, false_marks_per_case_max, time_per_case_max_s, "
           "normal_called_min)");
  }
  return b;
}

}  // namespace

const char* to_string(LevelCases kind) noexcept {
  switch (kind) {
    case LevelCases::generated_tumors: return "generated tumor cases";
    case LevelCases::generated_pulse: return "generated pulse cases";
    case LevelCases::scene_set: return "scene set";
  }
  return "generated tumor cases";
}

bool is_curriculum(const nlohmann::json& document) {
  const auto kind = document.find("kind");
  return document.is_object() && kind != document.end() && *kind == "curriculum";
}

Curriculum parse_curriculum(const nlohmann::json& document, const std::string& source,
                            const std::filesystem::path& base_dir) {
  const JsonObject root(document, source, "");
  root.require_version(kCurriculumFileVersion);
  Curriculum c;
  c.source = source;
  c.snapshot = document;
  (void)root.choice("kind", {"curriculum"});
  c.name = root.string("name");
  if (c.name.empty()) root.fail("name", "a non-empty curriculum name");
  c.description = root.string_or("description", "");
  c.tolerance_mm = root.number_or("tolerance_mm", 5.0, 0.0, 100.0);
  const auto levels = root.objects("levels");
  if (levels.empty()) root.fail("levels", "at least one level");
  if (levels.size() > kMaxLevels) root.fail("levels", "at most " + std::to_string(kMaxLevels) + " levels");
  std::set<std::string> names;
  for (const JsonObject& l : levels) {
    CurriculumLevel level;
    level.name = l.string("name");
    if (level.name.empty()) l.fail("name", "a non-empty level name");
    if (!names.insert(level.name).second) l.fail("name", "a name no other level has ('" + level.name + "' repeats)");
    read_cases(l, base_dir, level);
    level.cases_per_session = static_cast<int>(l.integer_or("cases_per_session", 4, 1, kMaxCasesPerSession));
    level.feedback = read_feedback(l);
    level.time_limit_s = l.number_or("time_limit_s", 120.0, 1.0, 3600.0);
    level.benchmark = read_benchmark(l);
    l.refuse_unknown();
    c.levels.push_back(std::move(level));
  }
  if (root.has("cusum")) {
    const JsonObject o = root.object("cusum");
    CurriculumCusum& k = c.cusum;
    k.acceptable_failure_rate = o.number_or("acceptable_failure_rate", k.acceptable_failure_rate, 0.001, 0.998);
    k.unacceptable_failure_rate = o.number_or("unacceptable_failure_rate", k.unacceptable_failure_rate, 0.002, 0.999);
    if (!(k.unacceptable_failure_rate > k.acceptable_failure_rate)) {
      o.fail("unacceptable_failure_rate",
             "a rate above acceptable_failure_rate (" + std::to_string(k.acceptable_failure_rate) + ")");
    }
    k.alpha = o.number_or("alpha", k.alpha, 0.001, 0.5);
    k.beta = o.number_or("beta", k.beta, 0.001, 0.5);
    k.horizon_cases = static_cast<int>(o.integer_or("horizon_cases", k.horizon_cases, 5, 2000));
    o.refuse_unknown();
  }
  if (root.has("pilot")) {
    const JsonObject o = root.object("pilot");
    c.pilot.initial_skill = o.number_or("initial_skill", c.pilot.initial_skill, 0.0, 1.0);
    c.pilot.learning_rate_per_case = o.number_or("learning_rate_per_case", c.pilot.learning_rate_per_case, 0.0, 10.0);
    o.refuse_unknown();
  }
  root.refuse_unknown();
  return c;
}

Curriculum load_curriculum(const std::filesystem::path& path) {
  const nlohmann::json document = read_json_file(path);
  return parse_curriculum(document, path.string(), path.parent_path());
}

int level_index(const Curriculum& curriculum, const std::string& name) {
  std::string known;
  for (std::size_t i = 0; i < curriculum.levels.size(); ++i) {
    if (curriculum.levels[i].name == name) return static_cast<int>(i);
    known += (known.empty() ? "" : ", ") + std::string("'") + curriculum.levels[i].name + "'";
  }
  throw InputError(curriculum.source, "level", "one of the curriculum's levels (" + known + "), got '" + name + "'");
}

}  // namespace palprig
