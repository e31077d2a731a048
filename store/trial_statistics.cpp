#include "store/trial_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "statistics/statistics_error.hpp"
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

// Per condition, the response time of every answered trial, once per trial (as summarise_trials
// counts them for its mean and sd).
std::map<std::string, std::vector<double>> response_times_by_condition(TrialStore& store, bool include_practice) {
  std::map<std::string, std::vector<double>> times;
  for (TrialFamily family : {TrialFamily::discrimination, TrialFamily::localisation}) {
    store.scan_scored_trials(family, include_practice, [&](const ScoredTrial& t) {
      auto& list = times[std::string(t.condition)];
      if (t.answered && std::isfinite(t.response_time_s)) list.push_back(t.response_time_s);
    });
  }
  return times;
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

  const auto times = response_times_by_condition(store, options.include_practice);
  const auto& rows = s.by_condition.rows;  // sorted by condition
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = i + 1; j < rows.size(); ++j) {
      const std::string& a = rows[i].key[0];
      const std::string& b = rows[j].key[0];
      ResponseTimeComparison rt{a, b, std::nullopt, {}};
      const auto ta = times.find(a), tb = times.find(b);
      const std::size_t na = ta == times.end() ? 0 : ta->second.size(), nb = tb == times.end() ? 0 : tb->second.size();
      if (na < 2 || nb < 2) {
        rt.why_not = "fewer than 2 answered trials in a condition";
      } else {
        try {
          rt.test = stats::two_sample_t_test(ta->second, tb->second, /*equal_variance=*/true, options.confidence);
        } catch (const stats::StatisticsError& e) {
          rt.why_not = e.what();
        }
      }
      s.response_times.push_back(std::move(rt));

      const std::pair<const char*, Measure DiagnosticMeasures::*> named[] = {{"Se", &DiagnosticMeasures::se},
                                                                             {"Sp", &DiagnosticMeasures::sp},
                                                                             {"PPV", &DiagnosticMeasures::ppv},
                                                                             {"ACC", &DiagnosticMeasures::acc}};
      for (const auto& [name, member] : named) {
        const Measure& ma = rows[i].measures.*member;
        const Measure& mb = rows[j].measures.*member;
        if (!ma.defined || !mb.defined) continue;  // no cases on a side: nothing to compare
        s.measures.push_back({name, a, b, stats::compare_proportions(ma.k, ma.n, mb.k, mb.n, options.confidence)});
      }
    }
  }
  return s;
}

}  // namespace palprig
