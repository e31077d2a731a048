#include "store/threshold_psychometric.hpp"

#include <fstream>
#include <limits>

#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {

double column_number(const ThresholdTrialRow& r, const std::string& column, const std::string& file) {
  if (column == "level_kPa") return r.trial.level_kPa;
  if (column == "correct") return r.trial.correct ? 1 : 0;
  if (column == "response") return r.trial.response;
  if (column == "reference_kPa") return r.trial.reference_kPa;
  throw InputError(file, "column '" + column + "'",
                   "a threshold_trials column: level_kPa, reference_kPa (levels); correct, response (responses)");
}

std::string column_label(const ThresholdTrialRow& r, const std::string& column, const std::string& file) {
  if (column.empty()) return "all";
  if (column == "track_name" || column == "track") return r.trial.track_name;
  if (column == "fingers") return r.trial.fingers;
  if (column == "participant") return r.participant;
  if (column == "session_id" || column == "session") return std::to_string(r.session_id);
  throw InputError(file, "column '" + column + "'",
                   "a threshold_trials group column: track_name, fingers, participant, session_id");
}

}  // namespace

bool is_sqlite_file(const std::filesystem::path& file) {
  // Only a regular file is sniffed: a FIFO would block here, a directory is no database.
  if (!regular_file_problem(file, std::numeric_limits<std::uintmax_t>::max()).empty()) return false;
  std::ifstream in(file, std::ios::binary);
  char magic[16] = {};
  in.read(magic, sizeof magic);
  return in.gcount() == 16 && std::string(magic, 15) == "SQLite format 3";
}

std::vector<ThresholdTrialRow> read_threshold_trials(const std::filesystem::path& file) {
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(file);
  ThresholdStore threshold(store, false);
  return threshold.trials();
}

std::vector<stats::PsychometricGroup> threshold_psychometric_groups(const std::vector<ThresholdTrialRow>& rows,
                                                                    const stats::PsychometricColumns& columns,
                                                                    const std::string& file) {
  const std::string level = columns.level.empty() ? "level_kPa" : columns.level;
  const std::string response = columns.response.empty() ? "correct" : columns.response;
  std::vector<std::string> labels;
  std::vector<double> levels;
  std::vector<int> responses;
  for (const ThresholdTrialRow& r : rows) {
    if (!r.trial.answered) continue;
    labels.push_back(column_label(r, columns.by, file));
    levels.push_back(column_number(r, level, file));
    responses.push_back(static_cast<int>(column_number(r, response, file)));
  }
  if (labels.empty()) throw InputError(file, "threshold_trials", "answered threshold trials (the database has none)");
  return stats::psychometric_groups(labels, levels, responses);
}

}  // namespace palprig
