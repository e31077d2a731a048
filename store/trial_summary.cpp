#include "store/trial_summary.hpp"

#include <algorithm>
#include <filesystem>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "core/input_error.hpp"

namespace palprig {

namespace {

constexpr std::size_t kKeyKinds = 6;

// Strings of one key kind, interned so the hot loop works on small integers.
class Interner {
 public:
  int id(std::string_view text) {
    for (std::size_t i = 0; i < values_.size(); ++i) {
      if (values_[i] == text) return static_cast<int>(i);
    }
    values_.emplace_back(text);
    return static_cast<int>(values_.size() - 1);
  }
  const std::string& text(int id) const { return values_[static_cast<std::size_t>(id)]; }

 private:
  std::vector<std::string> values_;
};

// A group's key as interned ids, only the requested kinds set (the others stay 0).
using GroupKey = std::array<int, kKeyKinds>;

struct GroupKeyHash {
  std::size_t operator()(const GroupKey& k) const noexcept {
    std::size_t h = 1469598103934665603ULL;
    for (int v : k) h = (h ^ static_cast<std::size_t>(v)) * 1099511628211ULL;
    return h;
  }
};

// Running mean and sd (Welford), over finite values only.
struct RunningMoments {
  std::int64_t n = 0;
  double mean = 0, m2 = 0;
  void add(double x) {
    if (!std::isfinite(x)) return;
    ++n;
    const double d = x - mean;
    mean += d / static_cast<double>(n);
    m2 += d * (x - mean);
  }
  double mean_or_nan() const { return n > 0 ? mean : std::numeric_limits<double>::quiet_NaN(); }
  double sd_or_nan() const {
    return n > 1 ? std::sqrt(m2 / static_cast<double>(n - 1)) : std::numeric_limits<double>::quiet_NaN();
  }
};

struct Accumulator {
  ConfusionCounts counts;
  std::int64_t trials = 0, unanswered = 0;
  RunningMoments rt, rt_after;  // from onset (paper 002) and from the stimulus end
  RunningMoments rt_reached;    // from when the stimulus reached the fingers
  std::int64_t rated = 0;
  double confidence_sum = 0;
  std::int64_t last_trial = -1;   // a trial adds its response time once per group
  bool localisation = false;      // holds localisation values
  std::int64_t normal_cases = 0;  // localisation: answered normal cases (TN: those left unmarked)

  void add_trial(const ScoredTrial& t) {
    if (t.trial_id == last_trial) return;
    last_trial = t.trial_id;
    ++trials;
    if (!t.answered) {
      ++unanswered;
      return;
    }
    rt.add(t.response_time_s);
    rt_after.add(t.rt_after_stimulus_s);
    rt_reached.add(t.rt_from_reached_s);
    if (t.confidence) {
      ++rated;
      confidence_sum += *t.confidence;
    }
  }
};

class Grouper {
 public:
  explicit Grouper(const std::vector<SummaryKey>& by) : by_(by) {}

  Accumulator& group(const std::array<int, kKeyKinds>& all_ids) {
    GroupKey key{};
    for (SummaryKey k : by_) key[static_cast<std::size_t>(k)] = all_ids[static_cast<std::size_t>(k)];
    // Consecutive units mostly share a group (a trial's fingers, a participant's trials):
    // the last one is remembered. unordered_map never moves its elements, so the pointer holds.
    if (last_ && key == last_key_) return *last_;
    last_key_ = key;
    last_ = &groups_[key];
    return *last_;
  }
  const std::unordered_map<GroupKey, Accumulator, GroupKeyHash>& groups() const { return groups_; }

 private:
  std::vector<SummaryKey> by_;
  std::unordered_map<GroupKey, Accumulator, GroupKeyHash> groups_;
  GroupKey last_key_{};
  Accumulator* last_ = nullptr;
};

// Interned id of a text column, remembering the last text seen (runs of equal values are the
// rule: one condition block after another).
class CachedIds {
 public:
  explicit CachedIds(Interner& names) : names_(names) {}
  int id(std::string_view text) {
    if (last_ >= 0 && text == last_text_) return last_;
    last_text_.assign(text);
    last_ = names_.id(text);
    return last_;
  }

 private:
  Interner& names_;
  std::string last_text_;
  int last_ = -1;
};

}  // namespace

const char* to_string(SummaryKey key) noexcept {
  switch (key) {
    case SummaryKey::condition: return "condition";
    case SummaryKey::participant: return "participant";
    case SummaryKey::finger: return "finger";
    case SummaryKey::tumor: return "tumor";
    case SummaryKey::combination: return "combination";
    case SummaryKey::session: return "session";
  }
  return "condition";
}

std::vector<SummaryKey> parse_summary_keys(const std::string& list) {
  std::vector<SummaryKey> keys;
  std::stringstream in(list);
  std::string word;
  while (std::getline(in, word, ',')) {
    if (word.empty()) continue;
    bool found = false;
    for (std::size_t k = 0; k < kKeyKinds; ++k) {
      if (word == to_string(static_cast<SummaryKey>(k))) {
        const auto key = static_cast<SummaryKey>(k);
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
        found = true;
      }
    }
    if (!found) {
      throw InputError("command line", "group_by",
                       "a list of condition, participant, finger, tumor, combination, session; got '" + word + "'");
    }
  }
  return keys;
}

namespace {

// A trial whose session row is missing: the database was edited or damaged in a way the
// page check cannot see. Refused by name rather than a bare std::out_of_range.
const std::pair<int, int>& session_of(const std::unordered_map<std::int64_t, std::pair<int, int>>& session_ids,
                                      std::int64_t session_id, const std::string& file, std::int64_t trial_id) {
  const auto it = session_ids.find(session_id);
  if (it == session_ids.end()) {
    throw InputError(file, "trials.session_id of trial " + std::to_string(trial_id),
                     "a session of the sessions table (session " + std::to_string(session_id) +
                         " is missing: the database was damaged or edited)");
  }
  return it->second;
}

// Per session, the name its trials' case had before trials stored it (schema 5): the stem of the
// protocol's one scene file.
std::unordered_map<std::int64_t, std::string> session_scene_names(TrialStore& store) {
  std::unordered_map<std::int64_t, std::string> names;
  for (const SessionOverview& s : store.list_sessions()) {
    if (s.task != "localisation") continue;
    const nlohmann::json snapshot = store.protocol_snapshot(s.id);
    const auto loc = snapshot.find("localisation");
    if (loc == snapshot.end() || !loc->is_object()) continue;
    const auto scene = loc->find("scene");
    if (scene != loc->end() && scene->is_string())
      names[s.id] = std::filesystem::path(scene->get<std::string>()).stem().string();
  }
  return names;
}

}  // namespace

TrialSummary summarise_trials(TrialStore& store, const SummaryOptions& options) {
  std::array<Interner, kKeyKinds> names;
  auto& conditions = names[static_cast<std::size_t>(SummaryKey::condition)];
  auto& participants = names[static_cast<std::size_t>(SummaryKey::participant)];
  auto& fingers = names[static_cast<std::size_t>(SummaryKey::finger)];
  auto& tumors = names[static_cast<std::size_t>(SummaryKey::tumor)];
  auto& combinations = names[static_cast<std::size_t>(SummaryKey::combination)];
  auto& sessions = names[static_cast<std::size_t>(SummaryKey::session)];
  const int no_tumor = tumors.id("-");
  const int no_finger = fingers.id("-");
  const int no_combination = combinations.id("-");
  std::array<int, kFingerCount> finger_ids{};
  for (int f = 0; f < kFingerCount; ++f) finger_ids[static_cast<std::size_t>(f)] = fingers.id(std::to_string(f + 1));

  // Session -> participant and session ids (few rows), so the trial scan needs no join.
  std::unordered_map<std::int64_t, std::pair<int, int>> session_ids;
  for (const SessionOverview& s : store.list_sessions()) {
    session_ids[s.id] = {participants.id(s.participant.code), sessions.id(std::to_string(s.id))};
  }

  Grouper grouper(options.by);

  // Discrimination: three finger values per trial.
  {
    CachedIds condition_ids(conditions), combination_ids(combinations);
    const bool by_combination =
        std::find(options.by.begin(), options.by.end(), SummaryKey::combination) != options.by.end();
    std::int64_t last_session = -1;
    std::pair<int, int> session_key{};
    store.scan_scored_trials(TrialFamily::discrimination, options.include_practice, [&](const ScoredTrial& t) {
      if (t.session_id != last_session) {
        last_session = t.session_id;
        session_key = session_of(session_ids, last_session, store.location(), t.trial_id);
      }
      const auto& [participant, session] = session_key;
      std::array<int, kKeyKinds> ids{};
      ids[static_cast<std::size_t>(SummaryKey::condition)] = condition_ids.id(t.condition);
      ids[static_cast<std::size_t>(SummaryKey::participant)] = participant;
      ids[static_cast<std::size_t>(SummaryKey::session)] = session;
      ids[static_cast<std::size_t>(SummaryKey::tumor)] = no_tumor;
      ids[static_cast<std::size_t>(SummaryKey::combination)] =
          !by_combination || !t.combination_label ? no_combination : combination_ids.id(*t.combination_label);
      for (int f = 0; f < kFingerCount; ++f) {
        ids[static_cast<std::size_t>(SummaryKey::finger)] = finger_ids[static_cast<std::size_t>(f)];
        Accumulator& a = grouper.group(ids);
        a.add_trial(t);
        if (const auto& o = t.finger_outcomes[static_cast<std::size_t>(f)]) a.counts.add(*o);
      }
    });
  }

  // Localisation: one value per tumor of each case (TP found, FN missed), keyed by case and
  // tumor (a "T1" of one generated case is not the "T1" of another); one FP per false mark; a
  // normal case answered without a mark is a TN. False marks and a normal case's answer are the
  // case's "elsewhere" row when grouping by tumor (never a tumor row of their own).
  const auto scene_names = session_scene_names(store);
  store.scan_scored_trials(TrialFamily::localisation, options.include_practice, [&](const ScoredTrial& t) {
    const auto& [participant, session] = session_of(session_ids, t.session_id, store.location(), t.trial_id);
    std::string case_name(t.case_name);
    if (case_name.empty()) {
      const auto it = scene_names.find(t.session_id);
      case_name = it == scene_names.end() ? std::string("scene") : it->second;
    }
    std::array<int, kKeyKinds> ids{};
    ids[static_cast<std::size_t>(SummaryKey::condition)] = conditions.id(t.condition);
    ids[static_cast<std::size_t>(SummaryKey::participant)] = participant;
    ids[static_cast<std::size_t>(SummaryKey::session)] = session;
    ids[static_cast<std::size_t>(SummaryKey::finger)] = no_finger;
    ids[static_cast<std::size_t>(SummaryKey::combination)] = no_combination;
    for (const ScoredTumor& score : t.tumors) {
      ids[static_cast<std::size_t>(SummaryKey::tumor)] = tumors.id(case_name + "/" + std::string(score.tumor));
      Accumulator& a = grouper.group(ids);
      a.localisation = true;
      a.add_trial(t);
      a.counts.add(score.outcome);
    }
    // A normal case (known to hold no tumor; stored before the column: had tumor scores), the
    // trial's false marks, and an unanswered trial, once.
    const bool normal = t.case_tumors ? *t.case_tumors == 0 : false;
    ids[static_cast<std::size_t>(SummaryKey::tumor)] = tumors.id(case_name + "/" + kElsewhereKey);
    if (!t.answered || t.false_marks > 0 || normal) {
      Accumulator& a = grouper.group(ids);
      a.localisation = true;
      a.add_trial(t);
      a.counts.fp += t.false_marks;
      if (normal && t.answered) {
        ++a.normal_cases;
        if (t.false_marks == 0) ++a.counts.tn;
      }
    }
  });

  TrialSummary summary;
  summary.by = options.by;
  for (const auto& [key, a] : grouper.groups()) {
    SummaryRow row;
    for (SummaryKey k : options.by) {
      row.key.push_back(names[static_cast<std::size_t>(k)].text(key[static_cast<std::size_t>(k)]));
    }
    row.counts = a.counts;
    row.measures = diagnostic_measures(a.counts, options.confidence);
    if (a.localisation) {
      // Specificity over the normal cases (a case correctly called normal); false marks count
      // against PPV. Without normal cases there is no denominator: n/a, never 0. ACC would add
      // tumors to cases: n/a.
      row.negatives_counted = a.normal_cases > 0;
      row.normal_cases = a.normal_cases;
      row.measures.sp =
          a.normal_cases > 0 ? proportion_measure(a.counts.tn, a.normal_cases, options.confidence) : Measure{};
      row.measures.acc = Measure{};
    }
    row.trials = a.trials;
    row.unanswered = a.unanswered;
    row.mean_rt_s = a.rt.mean_or_nan();
    row.sd_rt_s = a.rt.sd_or_nan();
    row.rt_count = a.rt.n;
    row.mean_rt_after_stimulus_s = a.rt_after.mean_or_nan();
    row.sd_rt_after_stimulus_s = a.rt_after.sd_or_nan();
    row.mean_rt_from_reached_s = a.rt_reached.mean_or_nan();
    row.sd_rt_from_reached_s = a.rt_reached.sd_or_nan();
    row.rated = a.rated;
    row.mean_confidence =
        a.rated > 0 ? a.confidence_sum / static_cast<double>(a.rated) : std::numeric_limits<double>::quiet_NaN();
    if (a.rated > 0) summary.any_rated = true;
    summary.rows.push_back(std::move(row));
  }
  std::sort(summary.rows.begin(), summary.rows.end(),
            [](const SummaryRow& a, const SummaryRow& b) { return a.key < b.key; });
  return summary;
}

}  // namespace palprig
