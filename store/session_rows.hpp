#pragma once
// A stored session as plain rows, store-neutral: what `palprig store copy` and `store sync`
// and the journal's pushes move between an SQLite file and a PostgreSQL server. The columns are
// the trial store's own (store/trial_store.hpp schema), listed once here with their types so
// each side reads and writes them typed (a double crosses as the same 64 bits).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace palprig {

using SqlValue = std::variant<std::monostate, std::int64_t, double, std::string>;
using SqlRow = std::vector<SqlValue>;

struct SqlColumn {
  const char* name;
  char type;  // 'i' integer, 'r' real, 't' text
};

// Session columns moved as they are (ids, participant and the lab columns are handled apart).
inline constexpr std::array<SqlColumn, 14> kSessionColumns{{{"protocol_name", 't'},
                                                            {"task", 't'},
                                                            {"bids_task", 't'},
                                                            {"protocol_json", 't'},
                                                            {"protocol_dir", 't'},
                                                            {"seed", 'i'},
                                                            {"condition_order", 't'},
                                                            {"rig_id", 't'},
                                                            {"rig_backend", 't'},
                                                            {"calibration", 't'},
                                                            {"participant_model", 't'},
                                                            {"status", 't'},
                                                            {"started_utc", 't'},
                                                            {"finished_utc", 't'}}};
inline constexpr std::size_t kSessionProtocolName = 0, kSessionSeed = 5, kSessionStatus = 11, kSessionStartedUtc = 12,
                             kSessionFinishedUtc = 13;

inline constexpr std::array<SqlColumn, 7> kPlannedColumns{{{"position", 'i'},
                                                           {"block", 'i'},
                                                           {"condition_index", 'i'},
                                                           {"condition", 't'},
                                                           {"practice", 'i'},
                                                           {"combination", 'i'},
                                                           {"break_after", 'i'}}};

// trials without id and session_id; position first. Later schemas appended columns at the end:
// confidence and stimulus_end_s with schema 2 (SQLite) / 3 (PostgreSQL), stimulus_reached_s
// with schema 4 / 5, the localisation case (case_name, case_seed, case_difficulty, case_tumors)
// with schema 5 / 6. A store older than a column has the ones before it only
// (trial_column_count) and reads the rest as NULL (trial_select_list).
inline constexpr std::array<SqlColumn, 30> kTrialColumns{{{"position", 'i'},
                                                          {"block", 'i'},
                                                          {"condition", 't'},
                                                          {"mode", 't'},
                                                          {"practice", 'i'},
                                                          {"combination", 'i'},
                                                          {"combination_label", 't'},
                                                          {"stimulus1_kPa", 'r'},
                                                          {"stimulus2_kPa", 'r'},
                                                          {"stimulus3_kPa", 'r'},
                                                          {"truth", 't'},
                                                          {"answered", 'i'},
                                                          {"answer", 't'},
                                                          {"response_time_s", 'r'},
                                                          {"onset_s", 'r'},
                                                          {"felt1_kPa", 'r'},
                                                          {"felt2_kPa", 'r'},
                                                          {"felt3_kPa", 'r'},
                                                          {"outcome1", 't'},
                                                          {"outcome2", 't'},
                                                          {"outcome3", 't'},
                                                          {"false_marks", 'i'},
                                                          {"completed_utc", 't'},
                                                          {"confidence", 'i'},
                                                          {"stimulus_end_s", 'r'},
                                                          {"stimulus_reached_s", 'r'},
                                                          {"case_name", 't'},
                                                          {"case_seed", 'i'},
                                                          {"case_difficulty", 't'},
                                                          {"case_tumors", 'i'}}};
inline constexpr std::size_t kTrialConfidence = 23, kTrialStimulusEnd = 24, kTrialStimulusReached = 25,
                             kTrialCaseName = 26, kTrialCaseSeed = 27, kTrialCaseDifficulty = 28, kTrialCaseTumors = 29;
// How many of kTrialColumns a store of each generation has.
inline constexpr std::size_t kTrialColumnsBeforeRating = kTrialConfidence,
                             kTrialColumnsBeforeReached = kTrialStimulusReached,
                             kTrialColumnsBeforeCase = kTrialCaseName;

// A training session's row (training_sessions without session_id), moved with its session: a
// trainee's history travels wherever the session goes (store copy, journal pushes).
inline constexpr std::array<SqlColumn, 10> kTrainingColumns{{{"trainee", 't'},
                                                             {"curriculum", 't'},
                                                             {"level", 'i'},
                                                             {"level_name", 't'},
                                                             {"cases", 't'},
                                                             {"status", 't'},
                                                             {"scores", 't'},
                                                             {"met_benchmark", 'i'},
                                                             {"started_utc", 't'},
                                                             {"finished_utc", 't'}}};
inline constexpr std::size_t kTrainingCases = 4, kTrainingStatus = 5;
// A trainee's enrolment in a curriculum (trainees).
inline constexpr std::array<SqlColumn, 3> kTraineeColumns{{{"code", 't'}, {"curriculum", 't'}, {"enrolled_utc", 't'}}};

inline constexpr std::array<SqlColumn, 3> kTumorScoreColumns{
    {{"tumor", 't'}, {"outcome", 't'}, {"nearest_mark_mm", 'r'}}};
inline constexpr std::array<SqlColumn, 4> kMarkColumns{{{"mark", 'i'}, {"x_mm", 'r'}, {"y_mm", 'r'}, {"tumor", 't'}}};

struct TrialRows {
  SqlRow trial;  // kTrialColumns
  std::vector<SqlRow> tumor_scores, marks;
  std::int64_t position() const { return std::get<std::int64_t>(trial.at(0)); }
};

struct SessionRows {
  std::string session_uid;  // global identity
  std::string host_name;    // '' when unknown (a plain file)
  std::string origin;       // 'palprig' or 'copy:<file>'
  std::string participant_code, participant_created_utc;
  bool simulated = false;
  SqlRow session;  // kSessionColumns
  std::vector<SqlRow> planned;
  std::vector<TrialRows> trials;   // by position; may start after 0 (a partial push)
  std::optional<SqlRow> training;  // kTrainingColumns, when the session is a trainee's

  const std::string& text(std::size_t column) const { return std::get<std::string>(session.at(column)); }
};

// The column list "a, b, c" of a table spec.
template <std::size_t N>
std::string column_list(const std::array<SqlColumn, N>& columns, const char* prefix = "") {
  std::string s;
  for (const SqlColumn& c : columns) {
    if (!s.empty()) s += ", ";
    s += prefix;
    s += c.name;
  }
  return s;
}

// kTrialColumns[from..] for a SELECT; a store that has only the first `present` of them gives
// NULL in place of the rest (typed for PostgreSQL with `typed_nulls`, as a scan's columns need).
inline std::string trial_select_list(std::size_t present, const char* prefix = "", std::size_t from = 0,
                                     bool typed_nulls = false) {
  std::string s;
  for (std::size_t i = from; i < kTrialColumns.size(); ++i) {
    if (!s.empty()) s += ", ";
    if (i >= present) {
      s += "NULL";
      if (typed_nulls) {
        const char type = kTrialColumns[i].type;
        s += type == 'i' ? "::integer" : type == 'r' ? "::double precision" : "::text";
      }
    } else {
      s += prefix;
      s += kTrialColumns[i].name;
    }
  }
  return s;
}

}  // namespace palprig
