#pragma once
// Statistics results as ordered JSON objects (the --json output of `palprig stats`, and what
// the GUI reads) and as aligned text. Every object names the test and its convention, so a
// reader of a saved result knows which defaults produced it.
#include <string>

#include <nlohmann/json.hpp>

#include "statistics/statistics_correlation.hpp"
#include "statistics/statistics_describe.hpp"
#include "statistics/statistics_proportion.hpp"
#include "statistics/statistics_rank_tests.hpp"
#include "statistics/statistics_ttest.hpp"

namespace palprig::stats {

using Report = nlohmann::ordered_json;

Report to_report(const WilsonInterval& w);
Report to_report(const ProportionComparison& c);
Report to_report(const TTestResult& t);
Report to_report(const MannWhitneyResult& m);
Report to_report(const SignedRankResult& w);
Report to_report(const PearsonResult& p);
Report to_report(const Description& d, QuantileRule rule);

// "key  value" lines; nested objects indent, arrays of objects print one block per element.
std::string render_text(const Report& report);

// Numbers for people: 6 significant digits, scientific below 1e-4 (p-values), "NA" for NaN.
std::string format_number(double x);

}  // namespace palprig::stats
