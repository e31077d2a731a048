#include "statistics/psychometric_groups.hpp"

#include <cmath>
#include <map>

#include "core/input_error.hpp"

namespace palprig::stats {

namespace {
constexpr int kMaxTrialsPerLevel = 1000000000;
}  // namespace

std::vector<PsychometricGroup> psychometric_groups(const CsvTable& table, const PsychometricColumns& a) {
  if (a.level.empty() || a.response.empty()) {
    throw InputError("command line", "level", "both the `level` and the `response` column for a CSV file");
  }
  const std::size_t level = table.column(a.level), response = table.column(a.response);
  const bool per_level = !a.n.empty(), grouped_by = !a.by.empty();
  const std::size_t n = per_level ? table.column(a.n) : 0, by = grouped_by ? table.column(a.by) : 0;
  std::vector<std::string> order;
  std::map<std::string, std::map<double, LevelCounts>> grouped;
  for (std::size_t row = 0; row < table.rows(); ++row) {
    const std::string label = grouped_by ? table.label(row, by) : "all";
    if (!grouped.count(label)) order.push_back(label);
    auto& c = grouped[label][table.number(row, level)];
    c.level = table.number(row, level);
    const double k = table.number(row, response);
    const std::string where = "line " + std::to_string(table.line_of_row(row));
    if (per_level) {
      const double trials = table.number(row, n);
      if (trials != std::floor(trials) || trials < 0 || k != std::floor(k) || k < 0 || k > trials) {
        throw InputError(table.source(), where + ", columns '" + a.response + "', '" + a.n + "'",
                         "whole counts with 0 <= " + a.response + " <= " + a.n);
      }
      // Counts are ints; a level's trials (summed over its rows) stay below 10^9.
      if (trials > kMaxTrialsPerLevel - c.n) {
        throw InputError(table.source(), where + ", column '" + a.n + "'",
                         "at most 1000000000 trials at one level (summed over its rows)");
      }
      c.n += static_cast<int>(trials);
      c.k += static_cast<int>(k);
    } else {
      if (k != 0 && k != 1) {
        throw InputError(table.source(), where + ", column '" + a.response + "'",
                         "a response of 0 or 1 per trial (or give the `n` column for counts per level), got " +
                             table.text(row, response));
      }
      if (c.n >= kMaxTrialsPerLevel) {
        throw InputError(table.source(), where, "at most 1000000000 trials at one level");
      }
      ++c.n;
      c.k += static_cast<int>(k);
    }
  }
  std::vector<PsychometricGroup> out;
  out.reserve(order.size());
  for (const auto& label : order) {
    PsychometricGroup g{label, {}};
    for (const auto& [x, c] : grouped[label]) g.counts.push_back(c);
    out.push_back(std::move(g));
  }
  return out;
}

std::vector<PsychometricGroup> psychometric_groups(const std::vector<std::string>& labels,
                                                   const std::vector<double>& levels,
                                                   const std::vector<int>& responses) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> x;
  std::map<std::string, std::vector<int>> y;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (!x.count(labels[i])) order.push_back(labels[i]);
    x[labels[i]].push_back(levels.at(i));
    y[labels[i]].push_back(responses.at(i));
  }
  std::vector<PsychometricGroup> out;
  out.reserve(order.size());
  for (const auto& label : order) out.push_back({label, counts_per_level(x[label], y[label])});
  return out;
}

namespace {

Report interval_report(const Interval& i) { return {{"low", i.low}, {"high", i.high}}; }

}  // namespace

Report psychometric_report(const PsychometricFit& f, double confidence) {
  Report r;
  r["sigmoid"] = to_string(f.sigmoid);
  r["trials"] = f.trials;
  r["alpha"] = f.alpha;
  r["beta"] = f.beta;
  r["guess"] = f.guess;
  r["guess_fitted"] = f.guess_fitted;
  r["lapse"] = f.lapse;
  r["lapse_fitted"] = f.lapse_fitted;
  r["threshold"] = f.threshold;
  r["threshold_proportion"] = f.threshold_proportion;
  r["slope"] = f.slope;
  r["jnd"] = f.jnd;
  r["confidence"] = confidence;
  r["bootstrap"] = f.bootstrap;
  r["bootstrap_failed"] = f.bootstrap_failed;
  r["alpha_ci"] = interval_report(f.alpha_ci);
  r["beta_ci"] = interval_report(f.beta_ci);
  r["threshold_ci"] = interval_report(f.threshold_ci);
  r["slope_ci"] = interval_report(f.slope_ci);
  r["jnd_ci"] = interval_report(f.jnd_ci);
  r["log_likelihood"] = f.log_likelihood;
  r["deviance"] = f.deviance;
  r["deviance_df"] = f.deviance_df;
  r["gof_p"] = f.gof_p;
  r["fit_seconds"] = f.fit_seconds;
  r["bootstrap_seconds"] = f.bootstrap_seconds;
  Report levels = Report::array();
  for (const auto& c : f.levels) {
    levels.push_back({{"level", c.level}, {"n", c.n}, {"k", c.k}, {"proportion", static_cast<double>(c.k) / c.n}});
  }
  r["levels"] = levels;
  return r;
}

}  // namespace palprig::stats
