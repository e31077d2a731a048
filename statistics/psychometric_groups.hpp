#pragma once
// The data of a psychometric fit, grouped: a CSV with one row per trial (a 0/1 response) or one
// row per level (the count of yes/correct answers and the number of trials), and parallel
// per-trial vectors (the trial store's threshold trials). Groups keep the order in which their
// labels first appear; levels within a group are sorted.
#include <string>
#include <vector>

#include "statistics/csv_table.hpp"
#include "statistics/psychometric_fit.hpp"
#include "statistics/statistics_report.hpp"

namespace palprig::stats {

struct PsychometricGroup {
  std::string label;  // "all" without a group column
  std::vector<LevelCounts> counts;
};

// Column names; `n` empty: one row per trial; `by` empty: one group.
struct PsychometricColumns {
  std::string level, response, n, by;
};

// Throws InputError naming the file, line and column of a row that is not a 0/1 response (or
// not whole counts 0 <= response <= n).
std::vector<PsychometricGroup> psychometric_groups(const CsvTable& table, const PsychometricColumns& columns);

// One group per label; trial i has level levels[i] and response responses[i] (0/1).
std::vector<PsychometricGroup> psychometric_groups(const std::vector<std::string>& labels,
                                                   const std::vector<double>& levels,
                                                   const std::vector<int>& responses);

// The fit as the report `palprig stats psychometric` prints (one object per group).
Report psychometric_report(const PsychometricFit& fit, double confidence);

}  // namespace palprig::stats
