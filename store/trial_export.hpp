#pragma once
// Exports of a trial database for analysts, every task kind the store holds.
//   long CSV  trials_long.csv: one row per scored unit, i.e. per finger value of a
//             discrimination trial (3 per trial) and per tumor of a localisation trial, with
//             participant, session, condition, stimulus, answer, outcome and times; marks.csv
//             lists localisation marks; threshold_trials.csv one row per threshold trial (track,
//             level, answer, reversal, the track's estimate after it: store/threshold_export.hpp);
//             pulse_trials.csv one row per pulse-localisation trial (store/pulse_export.hpp).
//             Each file is written only when the store holds trials of its kind.
//   BIDS      sub-<label>/beh/sub-<label>_task-<task>[_run-<n>]_beh.tsv, one row per trial, each
//             with a JSON sidecar describing every column (description, levels, units), plus
//             dataset_description.json, README and participants.tsv/json at the top
// Both write "n/a" for values that do not exist (an unanswered trial's response). A store with
// no trial to export is an InputError, never an empty export. Every file is written through
// ExportFile (store/export_file.hpp): a failed write is an OutputError naming the file, and
// leaves no file that looks complete.
#include <filesystem>
#include <string>
#include <vector>

#include "store/trial_store.hpp"

namespace palprig {

struct ExportOptions {
  bool include_practice = true;      // practice rows are marked by a column either way
  std::vector<std::string> authors;  // BIDS dataset_description Authors (empty: "Unknown ...")
  std::string dataset_name;          // BIDS Name (empty: "palprig trial export")
};

struct ExportResult {
  std::vector<std::filesystem::path> files;            // written, in order
  std::size_t trials = 0;                              // of every kind
  std::size_t threshold_trials = 0, pulse_trials = 0;  // of which
};

// `out_dir` is created when missing. Throws InputError when it cannot be written.
ExportResult export_long_csv(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options);
ExportResult export_bids(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options);

// A participant code as a BIDS label (letters and digits only): "sim:3" -> "sim3".
std::string bids_label_of(const std::string& code);

}  // namespace palprig
