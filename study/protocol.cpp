#include "study/protocol.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "formats/json_file.hpp"
#include "study/localisation_case.hpp"
#include "study/trial_order.hpp"
#include "core/input_error.hpp"
#include "study/session_bounds.hpp"

namespace palprig {

const char* to_string(TaskKind task) noexcept {
  return task == TaskKind::discrimination ? "discrimination" : "localisation";
}

const char* to_string(PresentationMode mode) noexcept {
  switch (mode) {
    case PresentationMode::simultaneous: return "simultaneous";
    case PresentationMode::sequential: return "sequential";
    case PresentationMode::scene: return "scene";
  }
  return "simultaneous";
}

namespace {

std::string format_kPa(double p) {
  std::ostringstream s;
  s << p;
  return s.str();
}

bool is_adjacent(int a, int b, const std::vector<std::pair<int, int>>& pairs) {
  for (const auto& [x, y] : pairs) {
    if ((x == a && y == b) || (x == b && y == a)) return true;
  }
  return false;
}

std::vector<std::pair<int, int>> read_adjacent_fingers(const JsonObject& root) {
  if (!root.has("adjacent_fingers")) return {{0, 1}, {1, 2}};
  const auto& raw = root.raw("adjacent_fingers");
  const std::string where = root.path("adjacent_fingers");
  if (!raw.is_array()) throw InputError(root.file(), where, "an array of finger pairs such as [[1, 2], [2, 3]]");
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const auto& p = raw[i];
    const bool ok = p.is_array() && p.size() == 2 && p[0].is_number_integer() && p[1].is_number_integer() &&
                    p[0].get<int>() >= 1 && p[0].get<int>() <= kFingerCount && p[1].get<int>() >= 1 &&
                    p[1].get<int>() <= kFingerCount && p[0].get<int>() != p[1].get<int>();
    if (!ok) {
      throw InputError(
          root.file(), where + "[" + std::to_string(i) + "]",
          "a pair of two different finger numbers 1.." + std::to_string(kFingerCount) + ", got " + p.dump());
    }
    pairs.emplace_back(p[0].get<int>() - 1, p[1].get<int>() - 1);
  }
  return pairs;
}

std::array<std::string, kFingerCount> read_finger_names(const JsonObject& root) {
  std::array<std::string, kFingerCount> names{"finger1", "finger2", "finger3"};
  if (!root.has("fingers")) return names;
  const auto& raw = root.raw("fingers");
  if (!raw.is_array() || raw.size() != kFingerCount) {
    throw InputError(root.file(), root.path("fingers"),
                     "an array of " + std::to_string(kFingerCount) + " finger names");
  }
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    if (!raw[i].is_string() || raw[i].get<std::string>().empty()) {
      throw InputError(root.file(), root.path("fingers") + "[" + std::to_string(i) + "]", "a non-empty name");
    }
    names[i] = raw[i].get<std::string>();
  }
  return names;
}

void read_combinations(const JsonObject& root, Protocol& p) {
  const JsonObject combos = root.object("combinations");
  p.combinations_how_chosen = combos.string("how_chosen");
  const auto& list = combos.raw("list_kPa");
  const std::string where = combos.path("list_kPa");
  if (!list.is_array() || list.empty())
    throw InputError(root.file(), where, "a non-empty array of [p1, p2, p3] in kPa");
  std::set<std::array<double, kFingerCount>> seen;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string at = where + "[" + std::to_string(i) + "]";
    const auto& entry = list[i];
    if (!entry.is_array() || entry.size() != kFingerCount) {
      throw InputError(root.file(), at,
                       "an array of " + std::to_string(kFingerCount) + " pressures in kPa, got " + entry.dump());
    }
    StimulusCombination c;
    for (std::size_t f = 0; f < kFingerCount; ++f) {
      const auto& v = entry[f];
      const bool is_level =
          v.is_number() && std::find(p.levels_kPa.begin(), p.levels_kPa.end(), v.get<double>()) != p.levels_kPa.end();
      if (!is_level)
        throw InputError(root.file(), at + "[" + std::to_string(f) + "]", "one of levels_kPa, got " + v.dump());
      c.pressure_kPa[f] = v.get<double>();
      c.label += (f ? "/" : "") + format_kPa(c.pressure_kPa[f]);
    }
    std::string reason;
    if (!classify_by_tumor_rule(c.pressure_kPa, p.adjacent_fingers, c.tumor, reason)) {
      throw InputError(root.file(), at, "a pattern the tumor rule classifies: " + reason);
    }
    if (!seen.insert(c.pressure_kPa).second)
      throw InputError(root.file(), at, "each combination once (" + c.label + " repeats)");
    p.combinations.push_back(c);
  }
  combos.refuse_unknown();
}

void read_conditions(const JsonObject& root, Protocol& p) {
  const auto list = root.objects("conditions");
  if (list.empty()) throw InputError(root.file(), root.path("conditions"), "at least one condition");
  std::set<std::string> names;
  for (const auto& c : list) {
    Condition cond;
    cond.name = c.string("name");
    if (cond.name.empty()) c.fail("name", "a non-empty condition name");
    if (!names.insert(cond.name).second) c.fail("name", "a name not used by another condition");
    if (p.task == TaskKind::discrimination) {
      cond.mode = c.choice("mode", {"simultaneous", "sequential"}) == "sequential" ? PresentationMode::sequential
                                                                                   : PresentationMode::simultaneous;
    } else {
      c.choice_or("mode", "scene", {"scene"});
      cond.mode = PresentationMode::scene;
    }
    c.refuse_unknown();
    p.conditions.push_back(cond);
  }
}

void read_timing(const JsonObject& root, Protocol& p) {
  if (!root.has("timing")) return;
  const JsonObject t = root.object("timing");
  Timing& d = p.timing;
  d.max_present_s = t.number_or("max_present_s", d.max_present_s, 0.1, 3600);
  if (p.task == TaskKind::discrimination) {
    d.sequential_step_s = t.number_or("sequential_step_s", d.sequential_step_s, 0.05, 600);
    d.sequential_gap_s = t.number_or("sequential_gap_s", d.sequential_gap_s, 0.0, 600);
    d.answer_during_stimulus = t.boolean_or("answer_during_stimulus", d.answer_during_stimulus);
  }
  d.response_timeout_s = t.number_or("response_timeout_s", d.response_timeout_s, 0.1, 3600);
  d.inter_trial_s = t.number_or("inter_trial_s", d.inter_trial_s, 0.0, 600);
  d.break_s = t.number_or("break_s", d.break_s, 0.0, 3600);
  t.refuse_unknown();
}

void read_randomisation(const JsonObject& root, Protocol& p) {
  if (!root.has("randomisation")) return;
  const JsonObject r = root.object("randomisation");
  const std::string scheme = r.choice_or("scheme", "full", {"fixed", "full", "blocked"});
  p.randomisation.scheme = scheme == "fixed"     ? RandomScheme::fixed
                           : scheme == "blocked" ? RandomScheme::blocked
                                                 : RandomScheme::full;
  p.randomisation.max_repeats_in_a_row = static_cast<int>(r.integer_or("max_repeats_in_a_row", 0, 0, 1000));
  p.randomisation.min_distance = static_cast<int>(r.integer_or("min_distance", 0, 0, 1000));
  r.refuse_unknown();
}

void read_confidence(const JsonObject& root, Protocol& p) {
  if (!root.has("confidence")) return;
  if (p.task != TaskKind::discrimination)
    root.fail("confidence", "no confidence rating (it is asked after a discrimination answer only)");
  const JsonObject c = root.object("confidence");
  p.confidence.levels = static_cast<int>(c.integer("levels", kMinConfidenceLevels, kMaxConfidenceLevels));
  if (c.has("labels")) {
    const auto& raw = c.raw("labels");
    if (!raw.is_array() || raw.size() != static_cast<std::size_t>(p.confidence.levels)) {
      c.fail("labels", "an array of exactly " + std::to_string(p.confidence.levels) + " labels (one per level), got " +
                           raw.dump());
    }
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (!raw[i].is_string() || raw[i].get<std::string>().empty()) {
        throw InputError(root.file(), c.path("labels") + "[" + std::to_string(i) + "]",
                         "a non-empty label, got " + raw[i].dump());
      }
      p.confidence.labels.push_back(raw[i].get<std::string>());
    }
  }
  c.refuse_unknown();
}

// "localisation": exactly one of "scene" (one case), "cases" (a set: file names or
// {"difficulty", "seed"} generated cases) or "generate" ({"difficulty"}: a new case per trial).
// A case without tumors is a normal case and is scored too ("nothing there" is its answer).
void read_localisation(const JsonObject& root, const std::filesystem::path& base_dir, Protocol& p) {
  const JsonObject loc = root.object("localisation");
  p.localisation.tolerance_mm = loc.number_or("tolerance_mm", 5.0, 0.0, 1000.0);
  const int given = (loc.has("scene") ? 1 : 0) + (loc.has("cases") ? 1 : 0) + (loc.has("generate") ? 1 : 0);
  if (given != 1) {
    loc.fail("scene",
             "exactly one of `scene` (a scene file), `cases` (a list of cases) or `generate` "
             "({\"difficulty\": ...}: a new generated case per trial)");
  }
  const auto resolve = [&](const std::filesystem::path& scene) {
    return scene.is_absolute() ? scene : base_dir / scene;
  };
  const auto difficulty_of = [&](const JsonObject& o) {
    return parse_difficulty(o.choice("difficulty", {"easy", "medium", "hard"}));
  };
  if (loc.has("scene")) {
    p.localisation.cases.push_back(file_localisation_case(resolve(loc.string("scene"))));
  } else if (loc.has("generate")) {
    const JsonObject g = loc.object("generate");
    p.localisation.generate = difficulty_of(g);
    g.refuse_unknown();
  } else {
    p.localisation.listed = true;
    const auto& list = loc.raw("cases");
    const std::string where = loc.path("cases");
    if (!list.is_array() || list.empty()) {
      throw InputError(root.file(), where,
                       "a non-empty array of cases: scene file names, or {\"difficulty\": ..., \"seed\": N} for a "
                       "generated case");
    }
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = where + "[" + std::to_string(i) + "]";
      LocalisationCase c;
      if (list[i].is_string()) {
        c = file_localisation_case(resolve(list[i].get<std::string>()));
      } else if (list[i].is_object()) {
        const JsonObject o(list[i], root.file(), at);
        const CaseDifficulty difficulty = difficulty_of(o);
        const auto seed = static_cast<std::uint64_t>(o.integer("seed", 0, 999999999999LL));
        o.refuse_unknown();
        c = generated_localisation_case(seed, difficulty);
      } else {
        throw InputError(root.file(), at,
                         "a scene file name or {\"difficulty\": ..., \"seed\": N}, got " + list[i].dump());
      }
      if (!names.insert(c.name).second) throw InputError(root.file(), at, "each case once (" + c.name + " repeats)");
      p.localisation.cases.push_back(std::move(c));
    }
  }
  loc.refuse_unknown();
}

// Refuse ordering constraints that no order of one condition's trials can meet.
void check_order_feasible(const Protocol& p) {
  const std::size_t kinds = static_cast<std::size_t>(order_items(p));
  const OrderConstraints constraints{p.randomisation.max_repeats_in_a_row, p.randomisation.min_distance};
  std::vector<std::string> names;
  for (const auto& c : p.combinations) names.push_back(c.label);
  if (p.localisation.listed) {
    for (const auto& c : p.localisation.cases) names.push_back(c.name);
  }
  if (names.empty()) names.push_back("the scene");
  const std::string where = "randomisation";
  const int reps = p.repetitions;
  switch (p.randomisation.scheme) {
    case RandomScheme::full: {
      if (auto why = order_infeasibility(std::vector<int>(kinds, reps), constraints, names)) {
        throw InputError(p.source, where, "constraints some order satisfies: " + *why);
      }
      break;
    }
    case RandomScheme::blocked: {
      // Each repetition is a shuffled run of every combination once: within a run nothing repeats,
      // across runs the best case keeps identical trials exactly `kinds` apart.
      if (auto why = order_infeasibility(std::vector<int>(kinds, 1), constraints, names)) {
        throw InputError(p.source, where, "constraints some order satisfies: " + *why);
      }
      if (reps > 1 && constraints.min_distance > static_cast<int>(kinds)) {
        throw InputError(p.source, where + ".min_distance",
                         "at most " + std::to_string(kinds) + " (blocked repetitions of " + std::to_string(kinds) +
                             " combinations cannot keep identical trials further apart)");
      }
      if (reps > 1 && kinds == 1 && constraints.max_repeats_in_a_row > 0 && reps > constraints.max_repeats_in_a_row) {
        throw InputError(
            p.source, where + ".max_repeats_in_a_row",
            "at least " + std::to_string(reps) + " (one combination repeated " + std::to_string(reps) + " times)");
      }
      break;
    }
    case RandomScheme::fixed: {
      std::vector<int> listed;
      for (int r = 0; r < reps; ++r) {
        for (std::size_t i = 0; i < kinds; ++i) listed.push_back(static_cast<int>(i));
      }
      if (!order_satisfies(listed, constraints)) {
        throw InputError(p.source, where, "constraints the fixed (listed) order satisfies");
      }
      break;
    }
  }
}

std::string bids_label(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c))) out += c;
  }
  return out;
}

}  // namespace

int order_items(const Protocol& p) noexcept {
  if (p.task == TaskKind::discrimination) return static_cast<int>(p.combinations.size());
  return p.localisation.listed ? static_cast<int>(p.localisation.cases.size()) : 1;
}

bool classify_by_tumor_rule(const std::array<double, kFingerCount>& pressure_kPa,
                            const std::vector<std::pair<int, int>>& adjacent_fingers, FingerFlags& tumor,
                            std::string& reason) {
  tumor.fill(false);
  const auto [lo_it, hi_it] = std::minmax_element(pressure_kPa.begin(), pressure_kPa.end());
  const double lo = *lo_it, hi = *hi_it;
  if (lo == hi) return true;  // all equal: no tumor
  std::vector<int> higher;
  for (int f = 0; f < kFingerCount; ++f) {
    const double p = pressure_kPa[static_cast<std::size_t>(f)];
    if (p != lo && p != hi) {
      reason = "three different pressures (the rule needs a background level and one higher level)";
      return false;
    }
    if (p == hi) higher.push_back(f);
  }
  if (higher.size() == 2 && !is_adjacent(higher[0], higher[1], adjacent_fingers)) {
    reason = "fingers " + std::to_string(higher[0] + 1) + " and " + std::to_string(higher[1] + 1) +
             " are higher but not adjacent (see adjacent_fingers)";
    return false;
  }
  for (int f : higher) tumor[static_cast<std::size_t>(f)] = true;
  return true;
}

Protocol parse_protocol(const nlohmann::json& document, const std::string& source,
                        const std::filesystem::path& base_dir) {
  const JsonObject root(document, source, "");
  root.require_version(kProtocolFileVersion);
  Protocol p;
  p.source = source;
  p.snapshot = document;
  p.name = root.string("name");
  if (p.name.empty()) root.fail("name", "a non-empty protocol name");
  p.description = root.string_or("description", "");
  p.task = root.choice("task", {"discrimination", "localisation"}) == "discrimination" ? TaskKind::discrimination
                                                                                       : TaskKind::localisation;
  p.bids_task = root.string_or("bids_task", bids_label(p.name));
  if (p.bids_task.empty() || bids_label(p.bids_task) != p.bids_task) {
    root.fail("bids_task", "letters and digits only (a BIDS task label), got \"" + p.bids_task + "\"");
  }
  p.finger_names = read_finger_names(root);

  if (p.task == TaskKind::discrimination) {
    p.adjacent_fingers = read_adjacent_fingers(root);
    p.levels_kPa = root.numbers("levels_kPa", 0.0, 100.0);
    if (p.levels_kPa.empty()) root.fail("levels_kPa", "at least one pressure level in kPa (the list is empty)");
    std::set<double> distinct(p.levels_kPa.begin(), p.levels_kPa.end());
    if (distinct.size() != p.levels_kPa.size()) root.fail("levels_kPa", "each level once");
    read_combinations(root, p);
  } else {
    read_localisation(root, base_dir, p);
  }

  read_conditions(root, p);
  p.repetitions = static_cast<int>(root.integer_or("repetitions", 1, 1, kMaxSessionTrials));
  p.blocks_per_condition = static_cast<int>(root.integer_or("blocks_per_condition", 1, 1, 1000));
  const std::size_t per_condition = static_cast<std::size_t>(p.repetitions) * static_cast<std::size_t>(order_items(p));
  if (per_condition % static_cast<std::size_t>(p.blocks_per_condition) != 0) {
    root.fail("blocks_per_condition",
              "a divisor of the " + std::to_string(per_condition) + " trials of each condition");
  }
  p.practice_trials = static_cast<int>(root.integer_or("practice_trials", 0, 0, 1000));
  const long long session_trials =
      static_cast<long long>(per_condition) * static_cast<long long>(p.conditions.size()) + p.practice_trials;
  if (session_trials > kMaxSessionTrials)
    root.fail("repetitions", "a protocol of " + session_bound_text(session_trials));
  p.break_every_trials = static_cast<int>(root.integer_or("break_every_trials", 0, 0, 100000));
  const std::string cb = root.choice_or("counterbalancing", "none", {"none", "alternate", "latin-square", "random"});
  p.counterbalancing = cb == "alternate"      ? Counterbalancing::alternate
                       : cb == "latin-square" ? Counterbalancing::latin_square
                       : cb == "random"       ? Counterbalancing::random
                                              : Counterbalancing::none;
  const std::string feedback = root.choice_or("feedback", "none", {"none", "practice", "all"});
  p.feedback = feedback == "all" ? Feedback::all : feedback == "practice" ? Feedback::practice : Feedback::none;
  read_randomisation(root, p);
  read_timing(root, p);
  read_confidence(root, p);
  root.refuse_unknown();
  check_order_feasible(p);
  return p;
}

Protocol load_protocol(const std::filesystem::path& path) {
  const nlohmann::json document = read_json_file(path);
  return parse_protocol(document, path.string(), path.parent_path());
}

}  // namespace palprig
