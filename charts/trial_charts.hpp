#pragma once
// Charts of a trial store's scores, drawn with chart_png.
#include <filesystem>

#include "store/trial_store.hpp"

namespace palprig::charts {

// Paper 002 fig. 15: Se, Sp, PPV and ACC per condition as bars with their Wilson 95 % intervals,
// written to dir/measures_by_condition.png (dir created when missing). Returns the file
// written. Throws InputError when the store has no scored trial.
std::filesystem::path plot_measures_by_condition(TrialStore& store, const std::filesystem::path& dir,
                                                 bool include_practice);

}  // namespace palprig::charts
