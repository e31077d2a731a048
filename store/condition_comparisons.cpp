#include "store/condition_comparisons.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "statistics/statistics_error.hpp"

namespace palprig {

const char* to_string(ResponseTimeTest test) noexcept { return test == ResponseTimeTest::welch ? "welch" : "student"; }

namespace {

ResponseTimeComparison compare_response_times(const SummaryRow& a, const SummaryRow& b, std::size_t condition,
                                              double confidence, ResponseTimeTest test) {
  ResponseTimeComparison rt{a.key[condition], b.key[condition], std::nullopt, {}};
  if (a.rt_count < 2 || b.rt_count < 2) {
    rt.why_not = "fewer than 2 answered trials in a condition";
    return rt;
  }
  try {
    rt.test = stats::two_sample_t_test_from_summary(a.mean_rt_s, a.sd_rt_s, static_cast<std::size_t>(a.rt_count),
                                                    b.mean_rt_s, b.sd_rt_s, static_cast<std::size_t>(b.rt_count),
                                                    test == ResponseTimeTest::student, confidence);
  } catch (const stats::StatisticsError& e) {
    rt.why_not = e.what();
  }
  return rt;
}

}  // namespace

ConditionComparisons compare_conditions(const TrialSummary& summary, double confidence, ResponseTimeTest test) {
  ConditionComparisons out;
  out.test = test;
  out.confidence = confidence;
  const auto at = std::find(summary.by.begin(), summary.by.end(), SummaryKey::condition);
  if (at == summary.by.end()) return out;
  out.by_condition = true;
  const std::size_t condition = static_cast<std::size_t>(at - summary.by.begin());
  for (SummaryKey k : summary.by)
    if (k != SummaryKey::condition) out.strata_by.push_back(k);

  // Rows of each stratum, in the summary's order (sorted by key, so conditions come sorted).
  std::map<std::vector<std::string>, std::vector<const SummaryRow*>> strata;
  for (const SummaryRow& row : summary.rows) {
    std::vector<std::string> key;
    for (std::size_t i = 0; i < row.key.size(); ++i)
      if (i != condition) key.push_back(row.key[i]);
    strata[key].push_back(&row);
  }
  const std::pair<const char*, Measure DiagnosticMeasures::*> named[] = {{"Se", &DiagnosticMeasures::se},
                                                                         {"Sp", &DiagnosticMeasures::sp},
                                                                         {"PPV", &DiagnosticMeasures::ppv},
                                                                         {"ACC", &DiagnosticMeasures::acc}};
  for (const auto& [key, rows] : strata) {
    if (rows.size() < 2) continue;
    ComparisonStratum stratum;
    stratum.key = key;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (std::size_t j = i + 1; j < rows.size(); ++j) {
        const SummaryRow& a = *rows[i];
        const SummaryRow& b = *rows[j];
        stratum.response_times.push_back(compare_response_times(a, b, condition, confidence, test));
        for (const auto& [name, member] : named) {
          const Measure& ma = a.measures.*member;
          const Measure& mb = b.measures.*member;
          if (!ma.defined || !mb.defined) continue;  // no cases on a side: nothing to compare
          stratum.measures.push_back({name, a.key[condition], b.key[condition],
                                      stats::compare_proportions(ma.k, ma.n, mb.k, mb.n, confidence)});
        }
      }
    }
    out.strata.push_back(std::move(stratum));
  }
  return out;
}

}  // namespace palprig

namespace palprig {

namespace {

std::string format(const char* pattern, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, pattern, value);
  return buf;
}

// p as a reader takes it in: four decimals, or two significant digits below 0.001.
std::string p_text(double p) { return p < 0.001 ? format("%.2e", p) : format("%.4f", p); }

std::string count_text(const stats::WilsonInterval& w) {
  return format("%.3f", w.p) + " (" + std::to_string(w.k) + "/" + std::to_string(w.n) + ")";
}

std::string percent(double confidence) { return std::to_string(static_cast<int>(std::lround(confidence * 100))); }

std::vector<std::string> response_time_cells(const ResponseTimeComparison& rt, double confidence, ResponseTimeTest t) {
  const std::string name = t == ResponseTimeTest::welch ? "Welch" : "Student";
  if (!rt.test) return {"RT s", "n/a", "n/a", "n/a", name + " t-test", rt.why_not};
  const stats::TTestResult& r = *rt.test;
  const bool different = r.p < 1.0 - confidence;
  return {"RT s",
          format("%.2f", r.mean_x) + " (n " + std::to_string(r.n_x) + ")",
          format("%.2f", r.mean_y) + " (n " + std::to_string(r.n_y) + ")",
          format("%.2f", r.estimate) + " [" + format("%.2f", r.ci_lower) + ", " + format("%.2f", r.ci_upper) + "]",
          name + " t(" + (t == ResponseTimeTest::welch ? format("%.1f", r.df) : format("%.0f", r.df)) +
              ") = " + format("%.2f", r.t),
          "p " + p_text(r.p) + (different ? ", different" : ", not different")};
}

std::vector<std::string> measure_cells(const MeasureComparison& m) {
  const stats::ProportionComparison& c = m.comparison;
  return {m.measure,
          count_text(c.first),
          count_text(c.second),
          format("%.3f", c.difference),
          "eq. 10 combined interval " + format("%.3f", c.combined_interval),
          c.significant ? "|difference| > interval, different" : "|difference| <= interval, not different"};
}

}  // namespace

std::string comparisons_table(const ConditionComparisons& c) {
  if (c.strata.empty()) return "";
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> header;
  for (SummaryKey k : c.strata_by) header.push_back(to_string(k));
  for (const char* h : {"conditions", "measure", "first", "second", "difference [CI]", "test", "result"})
    header.push_back(h);
  cells.push_back(header);
  for (const ComparisonStratum& s : c.strata) {
    auto add = [&](const std::string& first, const std::string& second, std::vector<std::string> rest) {
      std::vector<std::string> line = s.key;
      line.push_back(first);
      line.back().append(" vs ").append(second);
      line.insert(line.end(), rest.begin(), rest.end());
      cells.push_back(std::move(line));
    };
    for (const ResponseTimeComparison& rt : s.response_times)
      add(rt.first, rt.second, response_time_cells(rt, c.confidence, c.test));
    for (const MeasureComparison& m : s.measures) add(m.first, m.second, measure_cells(m));
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& line : cells)
    for (std::size_t i = 0; i < line.size(); ++i) width[i] = std::max(width[i], line[i].size());
  std::string out = "\nBetween conditions (paper 002; " + percent(c.confidence) +
                    " %): response times from onset, one per answered trial, by " +
                    (c.test == ResponseTimeTest::welch ? "Welch's t-test" : "Student's t-test (pooled variance)") +
                    "; Se, Sp, PPV, ACC by the combined interval of eq. 10\n";
  for (const auto& line : cells) {
    for (std::size_t i = 0; i < line.size(); ++i)
      out += line[i] + (i + 1 < line.size() ? std::string(width[i] - line[i].size() + 2, ' ') : "");
    out += "\n";
  }
  return out;
}

nlohmann::ordered_json comparisons_json(const ConditionComparisons& c) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  auto number_or_null = [](double x) -> nlohmann::ordered_json {
    if (std::isfinite(x)) return x;
    return nullptr;
  };
  for (const ComparisonStratum& s : c.strata) {
    auto base = [&](const std::string& first, const std::string& second, const std::string& measure) {
      nlohmann::ordered_json j;
      for (std::size_t i = 0; i < c.strata_by.size(); ++i) j[to_string(c.strata_by[i])] = s.key[i];
      j["first"] = first;
      j["second"] = second;
      j["measure"] = measure;
      return j;
    };
    for (const ResponseTimeComparison& rt : s.response_times) {
      nlohmann::ordered_json j = base(rt.first, rt.second, "RT");
      j["test"] = c.test == ResponseTimeTest::welch
                      ? "Welch two-sample t-test (R t.test; scipy ttest_ind equal_var=False)"
                      : "Student two-sample t-test, pooled variance (paper 002; scipy "
                        "ttest_ind)";
      if (rt.test) {
        const stats::TTestResult& r = *rt.test;
        j["n_first"] = r.n_x;
        j["n_second"] = r.n_y;
        j["mean_first_s"] = r.mean_x;
        j["mean_second_s"] = r.mean_y;
        j["difference_s"] = r.estimate;
        j["ci_lower_s"] = number_or_null(r.ci_lower);
        j["ci_upper_s"] = number_or_null(r.ci_upper);
        j["t"] = r.t;
        j["df"] = r.df;
        j["p"] = r.p;
        j["different"] = r.p < 1.0 - c.confidence;
      } else {
        j["why_not"] = rt.why_not;
      }
      out.push_back(std::move(j));
    }
    for (const MeasureComparison& m : s.measures) {
      nlohmann::ordered_json j = base(m.first, m.second, m.measure);
      const stats::ProportionComparison& p = m.comparison;
      j["test"] = "combined interval (paper 002 eq. 10)";
      j["k_first"] = p.first.k;
      j["n_first"] = p.first.n;
      j["k_second"] = p.second.k;
      j["n_second"] = p.second.n;
      j["p_first"] = p.first.p;
      j["p_second"] = p.second.p;
      j["difference"] = p.difference;
      j["combined_interval"] = p.combined_interval;
      j["different"] = p.significant;
      j["newcombe_lower"] = p.newcombe_lower;
      j["newcombe_upper"] = p.newcombe_upper;
      out.push_back(std::move(j));
    }
  }
  return out;
}

}  // namespace palprig
