#include "statistics/statistics_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace palprig::stats {

namespace {

// JSON has no NaN: a value that does not exist (sd of one value) is null.
nlohmann::ordered_json number_or_null(double x) {
  if (std::isfinite(x)) return x;
  return nullptr;
}

const char* rank_convention(bool continuity) {
  return continuity ? "R wilcox.test defaults: exact if n < 50 and untied (no zero differences), else normal "
                      "approximation with tie-corrected variance and continuity correction 0.5"
                    : "exact if n < 50 and untied (no zero differences), else normal approximation with "
                      "tie-corrected variance, no continuity correction (SPSS, scipy wilcoxon)";
}

void render(std::ostringstream& out, const Report& report, int indent) {
  const std::string pad(static_cast<std::size_t>(indent) * 2, ' ');
  for (auto it = report.begin(); it != report.end(); ++it) {
    const auto& value = it.value();
    if (value.is_object()) {
      out << pad << it.key() << ":\n";
      render(out, value, indent + 1);
    } else if (value.is_array() && !value.empty() && value.front().is_object()) {
      for (const auto& element : value) {
        out << pad << it.key() << ":\n";
        render(out, element, indent + 1);
      }
    } else {
      std::string text;
      if (value.is_number_float())
        text = format_number(value.get<double>());
      else if (value.is_string())
        text = value.get<std::string>();
      else if (value.is_null())
        text = "NA";
      else
        text = value.dump();
      out << pad << it.key() << std::string(it.key().size() < 22 ? 22 - it.key().size() : 1, ' ') << text << "\n";
    }
  }
}

}  // namespace

std::string format_number(double x) {
  if (std::isnan(x)) return "NA";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[40];
  if (x != 0.0 && std::fabs(x) < 1e-4)
    std::snprintf(buf, sizeof buf, "%.3e", x);
  else
    std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

Report to_report(const WilsonInterval& w) {
  Report r;
  r["test"] = "proportion";
  r["convention"] =
      "Wilson score interval without continuity correction (paper 002 eq. 9; statsmodels "
      "proportion_confint method='wilson'; R prop.test(correct=FALSE))";
  r["k"] = w.k;
  r["n"] = w.n;
  r["p"] = w.p;
  r["confidence"] = w.confidence;
  r["lower"] = w.lower;
  r["upper"] = w.upper;
  return r;
}

Report to_report(const ProportionComparison& c) {
  Report r;
  r["test"] = "compare-proportions";
  r["convention"] =
      "paper 002 eq. 10: CI = sqrt((P1-p1)^2 + (P2-p2)^2) from Wilson bounds facing each other, "
      "significant if |p1-p2| > CI; Newcombe (1998) hybrid score interval for p1-p2";
  r["first"] = to_report(c.first);
  r["second"] = to_report(c.second);
  r["first"].erase("test");
  r["first"].erase("convention");
  r["second"].erase("test");
  r["second"].erase("convention");
  r["difference"] = c.difference;
  r["combined_interval"] = c.combined_interval;
  r["significant"] = c.significant;
  r["newcombe_lower"] = c.newcombe_lower;
  r["newcombe_upper"] = c.newcombe_upper;
  return r;
}

Report to_report(const TTestResult& t) {
  Report r;
  r["test"] = to_string(t.kind);
  switch (t.kind) {
    case TTestKind::welch:
      r["convention"] = "unequal variances, Welch-Satterthwaite df (R t.test default; scipy ttest_ind equal_var=False)";
      break;
    case TTestKind::student:
      r["convention"] = "pooled variance, df = n1 + n2 - 2 (R t.test var.equal=TRUE; scipy ttest_ind default)";
      break;
    case TTestKind::paired:
      r["convention"] = "one-sample test of the differences x - y (R t.test paired=TRUE; scipy ttest_rel)";
      break;
    case TTestKind::one_sample:
      r["convention"] = "against a hypothesised mean (R t.test mu=; scipy ttest_1samp)";
      break;
  }
  r["alternative"] = "two-sided";
  r["n_x"] = t.n_x;
  if (t.kind != TTestKind::one_sample) r["n_y"] = t.n_y;
  r["mean_x"] = t.mean_x;
  r[t.kind == TTestKind::one_sample ? "mu" : "mean_y"] = t.mean_y;
  r["estimate"] = t.estimate;
  r["standard_error"] = t.standard_error;
  r["t"] = t.t;
  r["df"] = t.df;
  r["p"] = t.p;
  r["confidence"] = t.confidence;
  r["ci_lower"] = t.ci_lower;
  r["ci_upper"] = t.ci_upper;
  return r;
}

Report to_report(const MannWhitneyResult& m) {
  Report r;
  r["test"] = "Mann-Whitney U";
  r["convention"] = rank_convention(m.continuity_correction);
  r["alternative"] = "two-sided";
  r["n1"] = m.n1;
  r["n2"] = m.n2;
  r["U1"] = m.u1;
  r["U2"] = m.u2;
  r["U"] = m.u;
  r["z"] = m.z;
  r["p"] = m.p;
  r["p_method"] = m.exact ? "exact" : "normal";
  r["ties"] = m.ties;
  r["continuity_correction"] = m.continuity_correction;
  r["effect_r"] = m.effect_r;
  return r;
}

Report to_report(const SignedRankResult& w) {
  Report r;
  r["test"] = "Wilcoxon signed-rank";
  r["convention"] = rank_convention(w.continuity_correction);
  r["alternative"] = "two-sided";
  r["n"] = w.n;
  r["zeros_dropped"] = w.zeros;
  r["n_used"] = w.n_used;
  r["median_difference"] = w.median_difference;
  r["V"] = w.v;
  r["z"] = w.z;
  r["p"] = w.p;
  r["p_method"] = w.exact ? "exact" : "normal";
  r["ties"] = w.ties;
  r["continuity_correction"] = w.continuity_correction;
  r["effect_r"] = w.effect_r;
  return r;
}

Report to_report(const PearsonResult& p) {
  Report r;
  r["test"] = "Pearson correlation";
  r["convention"] = "t = r sqrt((n-2)/(1-r^2)), df = n-2, two-sided; Fisher z interval (R cor.test; scipy pearsonr)";
  r["n"] = p.n;
  r["r"] = p.r;
  r["t"] = number_or_null(p.t);
  r["df"] = p.df;
  r["p"] = p.p;
  r["confidence"] = p.confidence;
  r["ci_lower"] = number_or_null(p.ci_lower);
  r["ci_upper"] = number_or_null(p.ci_upper);
  return r;
}

Report to_report(const Description& d, QuantileRule rule) {
  Report r;
  r["n"] = d.n;
  r["mean"] = d.mean;
  r["sd"] = number_or_null(d.sd);
  r["min"] = d.min;
  r["q1"] = d.q1;
  r["median"] = d.median;
  r["q3"] = d.q3;
  r["max"] = d.max;
  r["iqr"] = d.iqr;
  r["quantile_rule"] = rule == QuantileRule::r_type7 ? "R type 7 (numpy default)" : "R type 6 (SPSS)";
  return r;
}

std::string render_text(const Report& report) {
  std::ostringstream out;
  render(out, report, 0);
  return out.str();
}

}  // namespace palprig::stats
