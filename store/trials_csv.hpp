#pragma once
// trials.csv of `palprig export`: one row per discrimination or localisation trial, beside
// trials_long.csv (one row per finger value or tumor). The unit of a response-time test is the
// trial: a t-test on the long file counts every trial three times (paper 002's three finger
// values) and, with practice kept, practice trials too. This file is what `stats ttest --column
// response_time_s --by condition` and R's t.test take as it is (filter practice == 0).
#include <filesystem>
#include <vector>

#include "store/trial_store.hpp"

namespace palprig {

// Writes `file` (through store/export_file: checked, no short file left) and adds it to
// `written`. `trials` in the export's order (participant, session, position).
void write_trials_csv(const std::vector<const StoredTrial*>& trials, const std::filesystem::path& file,
                      std::vector<std::filesystem::path>& written);

}  // namespace palprig
