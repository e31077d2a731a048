#pragma once
// Pulse-localisation sessions in the trial database: a `sessions` row (task "pulse", protocol
// snapshot, seed) and one `pulse_trials` row per trial, each committed in its own transaction
// (created on first use, like threshold_trials). The summary is what `palprig stats trials`
// prints for pulse sessions and the GUI's statistics view shows (the same call): hit rate per
// condition with its Wilson interval and n, and the mean, median and IQR of the mark's distance
// to the artery centreline (answered trials).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/pulse_protocol.hpp"
#include "study/pulse_record.hpp"
#include "store/sqlite_trial_store.hpp"

namespace palprig {

using StoredPulseSession = StoredTaskSession;

struct PulseConditionSummary {
  std::string condition;
  int trials = 0, answered = 0, hits = 0;
  double hit_rate = 0, hit_low = 0, hit_high = 0;  // hits / trials, Wilson interval
  double distance_mean_mm = 0;                     // NaN without answers
  double distance_median_mm = 0, distance_q1_mm = 0, distance_q3_mm = 0, distance_iqr_mm = 0;  // NaN without answers
};

class PulseStore {
 public:
  explicit PulseStore(SqliteTrialStore& store, bool writable = true);
  std::int64_t create_session(const ParticipantRecord& who, const PulseProtocol& protocol, std::uint64_t seed,
                              const SessionSetup& setup);
  StoredPulseSession load_session(std::int64_t session_id);
  void commit_trial(std::int64_t session_id, const PulseTrialRecord& trial);
  bool has_trials();
  // One session's committed trials in position order, as stored (the console's trial list after
  // a stop, and tests comparing sessions).
  std::vector<PulseTrialRecord> read_trials(std::int64_t session_id);
  std::vector<PulseConditionSummary> summarise(double confidence = 0.95);

 private:
  SqliteTrialStore& store_;
};

nlohmann::ordered_json pulse_summary_json(const std::vector<PulseConditionSummary>& rows, double confidence);
std::string pulse_summary_table(const std::vector<PulseConditionSummary>& rows, double confidence);

}  // namespace palprig
