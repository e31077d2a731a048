#pragma once
// One decoder of stored trial rows for both stores: the SQLite file (store/sqlite_trial_store)
// and the PostgreSQL lab server (store/postgres_trial_store) select the same columns in the
// same order (the k*Columns texts below) and hand each row to these functions through a small
// adapter (SqliteRow, PgRow: is_null, integer, real, text_view of a column). Written once, so
// `stats trials` and `export` read the same thing from either store.
//
// Templates rather than a virtual row interface: a scan of a million trials decodes about
// fifteen columns a row, and the adapters inline to the store's own accessors.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "store/trial_store.hpp"
#include "study/scoring.hpp"
#include "study/trial_record.hpp"

namespace palprig::trial_rows {

// The discrimination scan: these columns, then the later ones (confidence, stimulus_end_s,
// stimulus_reached_s).
inline constexpr const char* kScoredDiscriminationColumns =
    "t.id, t.session_id, t.condition, t.answered, t.response_time_s, t.outcome1, t.outcome2, t.outcome3, "
    "t.combination_label, t.onset_s, ";
// The localisation scan (one row per trial and tumor score), then the later ones.
inline constexpr const char* kScoredLocalisationColumns =
    "t.id, t.session_id, t.condition, t.answered, t.response_time_s, ts.tumor, ts.outcome, t.false_marks, "
    "t.onset_s, ";
// Every trial with its session and participant (export), then the later ones.
inline constexpr const char* kStoredTrialColumns =
    "p.code, p.simulated, p.number, s.id, s.protocol_name, s.task, s.bids_task, t.id, t.position, t.block, "
    "t.condition, t.mode, t.practice, t.combination, t.combination_label, t.stimulus1_kPa, t.stimulus2_kPa, "
    "t.stimulus3_kPa, t.felt1_kPa, t.felt2_kPa, t.felt3_kPa, t.truth, t.answered, t.answer, t.response_time_s, "
    "t.onset_s, t.outcome1, t.outcome2, t.outcome3, t.false_marks, t.completed_utc, ";

// " WHERE t.practice = 0" (or AND) unless practice trials are asked for.
inline std::string practice_filter(bool include_practice, const char* keyword) {
  return include_practice ? std::string() : std::string(" ") + keyword + " t.practice = 0";
}

// Finger flags as stored ("010": a tumor under the middle finger).
inline std::string flags_text(const FingerFlags& f) {
  std::string s;
  for (bool b : f) s += b ? '1' : '0';
  return s;
}

template <class Row>
double real_or_nan(const Row& row, int column) {
  return row.is_null(column) ? std::nan("") : row.real(column);
}

template <class Row>
std::optional<double> real_or_null(const Row& row, int column) {
  if (row.is_null(column)) return std::nullopt;
  return row.real(column);
}

// One row of the discrimination scan into `t` (views into the row: valid until the next row).
template <class Row>
void decode_scored_discrimination(const Row& q, ScoredTrial& t) {
  t.trial_id = q.integer(0);
  t.session_id = q.integer(1);
  t.condition = q.text_view(2);
  t.answered = q.integer(3) != 0;
  t.response_time_s = real_or_nan(q, 4);
  for (int f = 0; f < kFingerCount; ++f) {
    t.finger_outcomes[static_cast<std::size_t>(f)] =
        t.answered && !q.is_null(5 + f) ? outcome_from_string(q.text_view(5 + f)) : std::nullopt;
  }
  t.combination_label = q.is_null(8) ? std::nullopt : std::optional<std::string_view>(q.text_view(8));
  t.rt_after_stimulus_s = response_time_after_stimulus_s(q.real(9), t.response_time_s, real_or_nan(q, 11));
  t.rt_from_reached_s = response_time_from_reached_s(q.real(9), t.response_time_s, real_or_nan(q, 12));
  t.confidence = q.is_null(10) ? std::nullopt : std::optional<int>(static_cast<int>(q.integer(10)));
}

// The localisation scan gives one row per (trial, tumor score), ordered by trial: the rows of a
// trial are gathered and the trial handed to `visit` when the next one starts (and at finish()).
// The buffers are reused, so a long scan allocates only for its largest trial.
template <class Visit>
class LocalisationGatherer {
 public:
  explicit LocalisationGatherer(const Visit& visit) : visit_(visit) {}

  template <class Row>
  void add(const Row& q) {
    const std::int64_t trial_id = q.integer(0);
    if (!pending_ || trial_id != t_.trial_id) {
      finish();
      pending_ = true;
      tumor_count_ = 0;
      t_ = ScoredTrial{};
      t_.trial_id = trial_id;
      t_.session_id = q.integer(1);
      condition_.assign(q.text_view(2));
      t_.answered = q.integer(3) != 0;
      t_.response_time_s = real_or_nan(q, 4);
      t_.false_marks = q.is_null(7) ? 0 : q.integer(7);
      t_.rt_after_stimulus_s = response_time_after_stimulus_s(q.real(8), t_.response_time_s, real_or_nan(q, 10));
      t_.rt_from_reached_s = response_time_from_reached_s(q.real(8), t_.response_time_s, real_or_nan(q, 11));
      case_name_.assign(q.is_null(12) ? std::string_view() : q.text_view(12));
      t_.case_tumors = q.is_null(15) ? std::nullopt : std::optional<int>(static_cast<int>(q.integer(15)));
    }
    if (q.is_null(5)) return;
    const auto outcome = outcome_from_string(q.text_view(6));
    if (!outcome) return;
    if (tumor_names_.size() <= tumor_count_) tumor_names_.emplace_back();
    if (tumors_.size() <= tumor_count_) tumors_.emplace_back();
    tumor_names_[tumor_count_].assign(q.text_view(5));
    tumors_[tumor_count_].outcome = *outcome;
    ++tumor_count_;
  }

  // Hands on the trial gathered last, if any.
  void finish() {
    if (!pending_) return;
    tumors_.resize(tumor_count_);
    for (std::size_t i = 0; i < tumor_count_; ++i) tumors_[i].tumor = tumor_names_[i];
    t_.condition = condition_;
    t_.case_name = case_name_;
    t_.tumors = std::span<const ScoredTumor>(tumors_.data(), tumor_count_);
    visit_(t_);
    pending_ = false;
  }

 private:
  const Visit& visit_;
  ScoredTrial t_;
  std::string condition_, case_name_;
  std::vector<std::string> tumor_names_;  // the views in tumors_ point into it
  std::vector<ScoredTumor> tumors_;
  std::size_t tumor_count_ = 0;
  bool pending_ = false;
};

// One row of the trial read (export) as a StoredTrial; tumor scores and marks are read after.
template <class Row>
StoredTrial decode_stored_trial(const Row& q) {
  StoredTrial t;
  t.participant = std::string(q.text_view(0));
  t.simulated = q.integer(1) != 0;
  t.participant_number = static_cast<int>(q.integer(2));
  t.session = q.integer(3);
  t.protocol = std::string(q.text_view(4));
  t.task = std::string(q.text_view(5));
  t.bids_task = std::string(q.text_view(6));
  t.id = q.integer(7);
  t.position = static_cast<int>(q.integer(8));
  t.block = static_cast<int>(q.integer(9));
  t.condition = std::string(q.text_view(10));
  t.mode = std::string(q.text_view(11));
  t.practice = q.integer(12) != 0;
  t.combination = static_cast<int>(q.integer(13));
  t.combination_label = std::string(q.text_view(14));
  for (int f = 0; f < kFingerCount; ++f) {
    t.stimulus_kPa[static_cast<std::size_t>(f)] = real_or_null(q, 15 + f);
    t.felt_kPa[static_cast<std::size_t>(f)] = real_or_null(q, 18 + f);
    t.outcome[static_cast<std::size_t>(f)] = std::string(q.text_view(26 + f));
  }
  t.truth = std::string(q.text_view(21));
  t.answered = q.integer(22) != 0;
  t.answer = std::string(q.text_view(23));
  t.response_time_s = real_or_null(q, 24);
  t.onset_s = q.real(25);
  if (!q.is_null(29)) t.false_marks = q.integer(29);
  t.completed_utc = std::string(q.text_view(30));
  if (!q.is_null(31)) t.confidence = static_cast<int>(q.integer(31));
  t.stimulus_end_s = real_or_null(q, 32);
  if (t.answered && t.response_time_s && t.stimulus_end_s) {
    t.rt_after_stimulus_s = response_time_after_stimulus_s(t.onset_s, *t.response_time_s, *t.stimulus_end_s);
  }
  t.stimulus_reached_s = real_or_null(q, 33);
  if (t.answered && t.response_time_s && t.stimulus_reached_s) {
    t.rt_from_reached_s = response_time_from_reached_s(t.onset_s, *t.response_time_s, *t.stimulus_reached_s);
  }
  if (!q.is_null(34)) t.case_name = std::string(q.text_view(34));
  if (!q.is_null(35)) t.case_seed = static_cast<std::uint64_t>(q.integer(35));
  if (!q.is_null(36)) t.case_difficulty = std::string(q.text_view(36));
  if (!q.is_null(37)) t.case_tumors = static_cast<int>(q.integer(37));
  return t;
}

// A tumor score row (tumor, outcome) and a mark row (mark, x_mm, y_mm, tumor), from `first`.
template <class Row>
std::pair<std::string, std::string> decode_tumor_outcome(const Row& q, int first) {
  return {std::string(q.text_view(first)), std::string(q.text_view(first + 1))};
}

template <class Row>
StoredMark decode_mark(const Row& q, int first) {
  StoredMark m{static_cast<int>(q.integer(first)), q.real(first + 1), q.real(first + 2), std::nullopt};
  if (!q.is_null(first + 3)) m.tumor = std::string(q.text_view(first + 3));
  return m;
}

}  // namespace palprig::trial_rows
