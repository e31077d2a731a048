// `palprig stats psychometric` on a CSV: the table, its grouping into counts per level (per
// trial 0/1, or counts with an n column, by a group column), then the maximum-likelihood fit of
// every group (Ceres) with a small bootstrap. A StatisticsError is the command line's refusal
// (InputError naming the group, exit 2); a Ceres CHECK, an inf, a sanitizer report is a crash.
#include <cmath>

#include "fuzz/fuzz_input.hpp"
#include "statistics/csv_table.hpp"
#include "statistics/psychometric_fit.hpp"
#include "statistics/psychometric_groups.hpp"
#include "statistics/statistics_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte picks the sigmoid, guess and lapse handling; the rest is the CSV.
  const std::uint8_t mode = data[0];
  const std::string_view text = palprig::fuzz::text(data + 1, size - 1);
  palprig::fuzz::refused_or_read([&] {
    const palprig::CsvTable table = palprig::CsvTable::parse(text, "fuzz.csv");
    const auto& header = table.header();
    if (header.size() < 2) return;
    palprig::stats::PsychometricColumns columns{header[0], header[1], (mode & 1) && header.size() > 2 ? header[2] : "",
                                                (mode & 2) && header.size() > 3 ? header[3] : ""};
    for (const auto& group : palprig::stats::psychometric_groups(table, columns)) {
      palprig::stats::PsychometricOptions o;
      o.sigmoid = static_cast<palprig::stats::Sigmoid>((mode >> 2) % 3);
      if (mode & 16) o.guess.reset();
      if (mode & 32) o.lapse = 0.0;
      if (mode & 64) o.threshold_at = 0.75;
      o.bootstrap = (mode & 128) ? 5 : 0;
      try {
        const auto fit = palprig::stats::fit_psychometric(group.counts, o);
        if (!std::isfinite(fit.alpha) || !std::isfinite(fit.beta) || std::isinf(fit.threshold)) __builtin_trap();
        (void)palprig::stats::psychometric_report(fit, o.confidence);
      } catch (const palprig::stats::StatisticsError&) {
        // refused with a message: the command line's exit 2
      }
    }
  });
  return 0;
}
