#include "store/trial_statistics.hpp"

#include <algorithm>

#include "store/sqlite_trial_store.hpp"

namespace palprig {

namespace {

TrialSummary summary_by(TrialStore& store, SummaryOptions options, SummaryKey key) {
  options.by = {key};
  return summarise_trials(store, options);
}

// Rows keyed "-" belong to the other task (a localisation trial has no finger value, a
// discrimination trial no tumor), a case's "elsewhere" row to no tumor (its false marks, a normal
// case's answer); the view leaves them out of these two tables.
void drop_placeholder_rows(TrialSummary& summary) {
  const std::string elsewhere = std::string("/") + kElsewhereKey;
  std::erase_if(summary.rows, [&](const SummaryRow& r) {
    return !r.key.empty() && (r.key[0] == "-" || r.key[0].ends_with(elsewhere));
  });
}

}  // namespace

TrialStatistics compute_trial_statistics(TrialStore& store, const SummaryOptions& options) {
  TrialStatistics s;
  s.confidence = options.confidence;
  s.by_condition = summary_by(store, options, SummaryKey::condition);
  s.by_finger = summary_by(store, options, SummaryKey::finger);
  s.by_tumor = summary_by(store, options, SummaryKey::tumor);
  drop_placeholder_rows(s.by_finger);
  drop_placeholder_rows(s.by_tumor);
  if (auto* sqlite = dynamic_cast<SqliteTrialStore*>(&store))
    s.pulse = PulseStore(*sqlite, false).summarise(options.confidence);

  // The same call `palprig stats trials --by condition` makes: one stratum, every pair of
  // conditions, Student's t-test as in paper 002.
  ConditionComparisons between = compare_conditions(s.by_condition, options.confidence, ResponseTimeTest::student);
  if (!between.strata.empty()) {
    s.response_times = std::move(between.strata[0].response_times);
    s.measures = std::move(between.strata[0].measures);
  }
  return s;
}

}  // namespace palprig
