#pragma once
// Exports of a trial database for analysts.
//   long CSV  trials_long.csv: one row per scored unit, i.e. per finger value of a
//             discrimination trial (3 per trial) and per tumor of a localisation trial, with
//             participant, session, condition, stimulus, answer, outcome and times; marks.csv
//             lists localisation marks
//   BIDS      sub-<label>/beh/sub-<label>_task-<task>[_run-<n>]_beh.tsv, one row per trial, each
//             with a JSON sidecar describing every column (description, levels, units), plus
//             dataset_description.json and participants.tsv/json at the top
// Both write "n/a" for values that do not exist (an unanswered trial's response).
#include <filesystem>
#include <string>
#include <vector>

#include "store/trial_store.hpp"

namespace palprig {

struct ExportOptions {
  bool include_practice = true;  // practice rows are marked by a column either way
};

struct ExportResult {
  std::vector<std::filesystem::path> files;  // written, in order
  std::size_t trials = 0;
};

// `out_dir` is created when missing. Throws InputError when it cannot be written.
ExportResult export_long_csv(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options);
ExportResult export_bids(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options);

// A participant code as a BIDS label (letters and digits only): "sim:3" -> "sim3".
std::string bids_label_of(const std::string& code);

}  // namespace palprig
