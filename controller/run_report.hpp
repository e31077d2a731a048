#pragma once
// A run's summary for people (the table `palprig run` and `palprig demo` print) and for
// programs (the JSON of --json): rate, overruns, pressures per finger, latencies, faults.
#include <iosfwd>

#include <nlohmann/json.hpp>

#include "controller/run_setup.hpp"

namespace palprig {

nlohmann::json run_summary_json(const RunSummary& s, const LoadedRun& run, const RunOptions& opt);
void print_run_summary(std::ostream& out, const RunSummary& s, const LoadedRun& run, const RunOptions& opt);

}  // namespace palprig
