#pragma once
// What the `palprig stats` subcommands share: printing a report (text or --json), turning a
// statistics refusal into an input refusal, and the rank-test options.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "core/input_error.hpp"
#include "statistics/statistics_error.hpp"
#include "statistics/statistics_report.hpp"
#include "statistics/statistics_rank_tests.hpp"

namespace palprig::cli {

inline void print(const stats::Report& report, bool json) {
  if (json)
    std::cout << report.dump(2) << "\n";
  else
    std::cout << stats::render_text(report);
}

// Run a computation; a StatisticsError (too few values, constant data) becomes a refusal of
// the input that names the file and the column.
template <class Compute>
inline stats::Report refuse_bad_data(const std::string& file, const std::string& where, Compute compute) {
  try {
    return compute();
  } catch (const stats::StatisticsError& e) {
    throw InputError(file, where, e.what());
  }
}

inline stats::RankOptions rank_options(const std::string& method, bool no_correction) {
  stats::RankOptions o;
  o.method = method == "exact"    ? stats::RankMethod::exact
             : method == "normal" ? stats::RankMethod::normal
                                  : stats::RankMethod::automatic;
  o.continuity_correction = !no_correction;
  return o;
}

inline void add_rank_options(CLI::App* sub, std::string& method, bool& no_correction) {
  sub->add_option("--method", method,
                  "auto: exact p when every sample has < 50 values and there are no ties (or zero differences), "
                  "else normal approximation (R wilcox.test default); exact; normal")
      ->check(CLI::IsMember({"auto", "exact", "normal"}))
      ->default_val("auto");
  sub->add_flag("--no-correction", no_correction,
                "Normal approximation without the 0.5 continuity correction (SPSS; scipy wilcoxon default). "
                "Default: corrected, as R wilcox.test and scipy mannwhitneyu");
}

// --confidence: a level strictly between 0 and 1. Checked by the command line (CLI11's Range
// lets NaN through), so the refusal names the option rather than the data it would be used on.
inline const CLI::Validator kConfidenceLevel(
    [](std::string& text) -> std::string {
      std::size_t used = 0;
      double level = 0;
      try {
        level = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || !(level > 0.0 && level < 1.0)) {
        return "a confidence level strictly between 0 and 1 (e.g. 0.95), got '" + text.substr(0, 40) + "'";
      }
      return {};
    },
    "(0 < LEVEL < 1)");

}  // namespace palprig::cli
