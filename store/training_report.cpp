#include "store/training_report.hpp"
#include "store/export_text.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace palprig {

namespace {

using export_text::fixed;

std::string point_text(const stats::LearningPoint& p, int decimals, bool interval) {
  if (!p.defined) return "n/a";
  std::string s = fixed(p.value, decimals);
  if (interval) s += " [" + fixed(p.lower, decimals) + ", " + fixed(p.upper, decimals) + "]";
  return s;
}

nlohmann::ordered_json point_json(const stats::LearningPoint& p) {
  if (!p.defined) return nullptr;
  return {{"value", p.value}, {"lower", p.lower}, {"upper", p.upper}, {"n", p.n}};
}

nlohmann::ordered_json optional_json(const std::optional<double>& x) {
  return x ? nlohmann::ordered_json(*x) : nlohmann::ordered_json(nullptr);
}

// "at case 14, 30", or `none`.
std::string signals_text(const std::vector<stats::CusumPoint>& points, const std::string& none) {
  std::string s;
  for (const auto& p : points) {
    if (p.signal) s += (s.empty() ? "" : ", ") + std::to_string(p.case_number);
  }
  return s.empty() ? none : "at case " + s;
}

nlohmann::ordered_json limit_json(const stats::CusumLimit& l) {
  return {{"chart", stats::to_string(l.chart)},
          {"acceptable_failure_rate", l.rates.acceptable_failure},
          {"unacceptable_failure_rate", l.rates.unacceptable_failure},
          {"alpha", l.errors.alpha},
          {"beta", l.errors.beta},
          {"horizon_cases", l.errors.horizon_cases},
          {"limit", l.limit},
          {"wald_limit", l.wald_limit},
          {"false_signal_within_horizon", l.false_signal_within},
          {"true_signal_within_horizon", l.true_signal_within},
          {"mean_cases_to_true_signal", optional_json(l.mean_cases_to_true_signal)},
          {"cases_for_power",
           l.cases_for_power ? nlohmann::ordered_json(*l.cases_for_power) : nlohmann::ordered_json(nullptr)}};
}

}  // namespace

std::string cusum_limits_text(const stats::CusumLimit& cusum, const stats::CusumLimit& lc) {
  std::ostringstream out;
  const auto line = [&](const stats::CusumLimit& l, const char* false_what, const char* true_what) {
    out << "  " << stats::to_string(l.chart) << ": h = " << fixed(l.limit, 2) << " (Wald " << fixed(l.wald_limit, 2)
        << "); within " << l.errors.horizon_cases << " cases " << false_what << " " << fixed(l.false_signal_within, 3)
        << " (alpha " << fixed(l.errors.alpha, 3) << "), " << true_what << " " << fixed(l.true_signal_within, 3)
        << " (1 - beta " << fixed(1 - l.errors.beta, 3) << "); mean "
        << (l.mean_cases_to_true_signal ? fixed(*l.mean_cases_to_true_signal, 1) : std::string("n/a"))
        << " cases to a true signal, " << (l.cases_for_power ? std::to_string(*l.cases_for_power) : "n/a")
        << " for probability 1 - beta\n";
  };
  out << "CUSUM limits (acceptable failure rate " << fixed(lc.rates.acceptable_failure, 2) << ", unacceptable "
      << fixed(lc.rates.unacceptable_failure, 2) << "):\n";
  line(lc, "a trainee failing at the unacceptable rate declared competent", "one at the acceptable rate");
  line(cusum, "a false alarm at the acceptable rate", "an alarm at the unacceptable rate");
  return out.str();
}

std::string learning_report_text(const Curriculum& curriculum, const std::vector<TraineeStanding>& trainees) {
  std::ostringstream out;
  bool limits_said = false;
  for (const TraineeStanding& t : trainees) {
    const TrainingCurves c = training_curves(curriculum, t);
    if (!limits_said) {
      out << cusum_limits_text(c.cusum_limit, c.lc_cusum_limit);
      limits_said = true;
    }
    out << "trainee " << t.trainee << ": " << c.level.size() << " sessions, " << c.case_failures.size()
        << " cases; LC-CUSUM: competence declared " << signals_text(c.lc_cusum, "not yet") << "; CUSUM: alarm "
        << signals_text(c.cusum, "none") << "\n";
    char head[256];
    std::snprintf(head, sizeof head, "  %-8s %-6s %-22s %-12s %-10s %-14s %s\n", "session", "level", "found [95% CI]",
                  "marks/case", "s/case", "normal called", "benchmark");
    out << head;
    for (std::size_t i = 0; i < c.level.size(); ++i) {
      char row[256];
      std::snprintf(row, sizeof row, "  %-8zu %-6d %-22s %-12s %-10s %-14s %s\n", i + 1, c.level[i] + 1,
                    point_text(c.found[i], 2, true).c_str(), point_text(c.false_marks[i], 2, false).c_str(),
                    point_text(c.time_per_case[i], 1, false).c_str(), point_text(c.normal_called[i], 2, false).c_str(),
                    c.met[i] ? "met" : "not met");
      out << row;
    }
  }
  if (trainees.empty()) out << "no trainee enrolled in '" << curriculum.name << "'\n";
  return out.str();
}

nlohmann::ordered_json learning_report_json(const Curriculum& curriculum,
                                            const std::vector<TraineeStanding>& trainees) {
  nlohmann::ordered_json j;
  j["curriculum"] = curriculum.name;
  j["convention"] =
      "per session: tumors found of all tumors (Wilson interval), false marks and seconds per case (mean, Student t "
      "interval), normal cases called normal; per case a failure unless every tumor was found (a normal case left "
      "unmarked, a pulse hit) with no more false marks than the level allows; CUSUM (Page; Biau et al. 2007) and "
      "LC-CUSUM (Biau et al. 2008) over the cases, limits from alpha over the horizon";
  j["trainees"] = nlohmann::ordered_json::array();
  for (const TraineeStanding& t : trainees) {
    const TrainingCurves c = training_curves(curriculum, t);
    if (!j.contains("cusum_limit")) {
      j["cusum_limit"] = limit_json(c.cusum_limit);
      j["lc_cusum_limit"] = limit_json(c.lc_cusum_limit);
    }
    nlohmann::ordered_json tj{{"trainee", t.trainee},
                              {"level", t.standing.level},
                              {"finished", t.standing.finished},
                              {"sessions", nlohmann::ordered_json::array()}};
    for (std::size_t i = 0; i < c.level.size(); ++i) {
      tj["sessions"].push_back({{"session", i + 1},
                                {"level", c.level[i]},
                                {"found", point_json(c.found[i])},
                                {"false_marks_per_case", point_json(c.false_marks[i])},
                                {"time_per_case_s", point_json(c.time_per_case[i])},
                                {"normal_called", point_json(c.normal_called[i])},
                                {"found_min", optional_json(c.found_min[i])},
                                {"false_marks_max", optional_json(c.false_marks_max[i])},
                                {"time_max_s", optional_json(c.time_max_s[i])},
                                {"normal_called_min", optional_json(c.normal_called_min[i])},
                                {"met_benchmark", bool(c.met[i])}});
    }
    nlohmann::ordered_json cusum = nlohmann::ordered_json::array(), lc = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < c.cusum.size(); ++i) {
      cusum.push_back({{"case", c.cusum[i].case_number},
                       {"failure", c.cusum[i].failure},
                       {"value", c.cusum[i].value},
                       {"signal", c.cusum[i].signal}});
      lc.push_back({{"case", c.lc_cusum[i].case_number},
                    {"failure", c.lc_cusum[i].failure},
                    {"value", c.lc_cusum[i].value},
                    {"signal", c.lc_cusum[i].signal}});
    }
    tj["cusum"] = cusum;
    tj["lc_cusum"] = lc;
    j["trainees"].push_back(tj);
  }
  return j;
}

}  // namespace palprig
