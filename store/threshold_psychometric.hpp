#pragma once
// The trial store's threshold trials as psychometric data: the answered trials of a database
// grouped by a threshold_trials column (track_name, fingers, participant, session_id), levels
// and responses from its columns (level_kPa or reference_kPa; correct or response).
#include <filesystem>
#include <string>
#include <vector>

#include "statistics/psychometric_groups.hpp"
#include "store/threshold_store.hpp"

namespace palprig {

// True when the file starts with SQLite's magic (a trial database rather than a CSV).
bool is_sqlite_file(const std::filesystem::path& file);

// Every threshold trial of the database at `file` (read only).
std::vector<ThresholdTrialRow> read_threshold_trials(const std::filesystem::path& file);

// Columns empty: level_kPa, correct, one group. Throws InputError naming `file` and the column
// for an unknown column, or when no trial was answered.
std::vector<stats::PsychometricGroup> threshold_psychometric_groups(const std::vector<ThresholdTrialRow>& rows,
                                                                    const stats::PsychometricColumns& columns,
                                                                    const std::string& file);

}  // namespace palprig
