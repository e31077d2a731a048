#include "store/sqlite_trial_store.hpp"

// Reading an SQLite trial store for stats and export: sessions, protocol snapshots, the scored
// scans and whole trials, decoded by store/trial_rows.hpp as the PostgreSQL store decodes them.
#include <filesystem>
#include <system_error>

#include "core/input_error.hpp"
#include "store/session_rows.hpp"
#include "store/trial_rows.hpp"

namespace palprig {

std::vector<SessionOverview> SqliteTrialStore::list_sessions() {
  std::vector<SessionOverview> sessions;
  auto q = db_.prepare(
      "SELECT s.id, p.id, p.code, p.number, p.simulated, s.protocol_name, s.task, s.bids_task, s.status "
      "FROM sessions s JOIN participants p ON p.id = s.participant_id ORDER BY s.id");
  while (q.step()) {
    sessions.push_back(SessionOverview{
        q.integer(0), ParticipantRecord{q.integer(1), q.text(2), static_cast<int>(q.integer(3)), q.integer(4) != 0},
        q.text(5), q.text(6), q.text(7), q.text(8)});
  }
  return sessions;
}

nlohmann::json SqliteTrialStore::protocol_snapshot(std::int64_t session_id) {
  auto q = db_.prepare("SELECT protocol_json FROM sessions WHERE id = ?1");
  q.bind(1, session_id);
  if (!q.step()) throw InputError(db_.file(), "session " + std::to_string(session_id), "an existing session");
  // A snapshot that no longer parses is reported as null: readers fall back to defaults.
  return nlohmann::json::parse(q.text_view(0), nullptr, false);
}

std::string SqliteTrialStore::later_columns(const char* prefix) const {
  // An older file read as it is: the columns it lacks read as NULL.
  return trial_select_list(trial_columns_, prefix, kTrialColumnsBeforeRating);
}

namespace {

// A statement's current row as the decoders of store/trial_rows.hpp read it.
struct SqliteRow {
  const Statement& q;
  bool is_null(int c) const noexcept { return q.is_null(c); }
  std::int64_t integer(int c) const noexcept { return q.integer(c); }
  double real(int c) const noexcept { return q.real(c); }
  std::string_view text_view(int c) const noexcept { return q.text_view(c); }
};

}  // namespace

void SqliteTrialStore::scan_scored_trials(TrialFamily family, bool include_practice,
                                          const std::function<void(const ScoredTrial&)>& visit) {
  using namespace trial_rows;
  if (family == TrialFamily::discrimination) {
    auto q = db_.prepare(std::string("SELECT ") + kScoredDiscriminationColumns + later_columns("t.") +
                         " FROM trials t WHERE t.mode != 'scene'" + practice_filter(include_practice, "AND"));
    ScoredTrial t;
    while (q.step()) {
      decode_scored_discrimination(SqliteRow{q}, t);
      visit(t);
    }
    return;
  }
  auto q = db_.prepare(std::string("SELECT ") + kScoredLocalisationColumns + later_columns("t.") +
                       " FROM trials t LEFT JOIN tumor_scores ts ON ts.trial_id = t.id WHERE t.mode = 'scene'" +
                       practice_filter(include_practice, "AND") + " ORDER BY t.id");
  LocalisationGatherer gather(visit);
  while (q.step()) gather.add(SqliteRow{q});
  gather.finish();
}

std::vector<StoredTrial> SqliteTrialStore::read_trials(bool include_practice) {
  return read_trials_where(trial_rows::practice_filter(include_practice, "WHERE"));
}

std::vector<StoredTrial> SqliteTrialStore::read_session_trials(std::int64_t session_id) {
  return read_trials_where(" WHERE s.id = " + std::to_string(session_id));
}

int SqliteTrialStore::next_participant_number() {
  auto next = db_.prepare("SELECT COALESCE(MAX(number), 0) + 1 FROM participants");
  next.step();
  return static_cast<int>(next.integer(0));
}

std::vector<StoredTrial> SqliteTrialStore::read_trials_where(const std::string& where) {
  using namespace trial_rows;
  std::vector<StoredTrial> trials;
  auto q = db_.prepare(
      std::string("SELECT ") + kStoredTrialColumns + later_columns("t.") +
      " FROM trials t JOIN sessions s ON s.id = t.session_id JOIN participants p ON p.id = s.participant_id" + where +
      " ORDER BY p.number, s.id, t.position");
  while (q.step()) trials.push_back(decode_stored_trial(SqliteRow{q}));
  auto ts = db_.prepare("SELECT tumor, outcome FROM tumor_scores WHERE trial_id = ?1 ORDER BY tumor");
  auto mk = db_.prepare("SELECT mark, x_mm, y_mm, tumor FROM marks WHERE trial_id = ?1 ORDER BY mark");
  for (StoredTrial& t : trials) {
    if (t.mode != "scene") continue;
    ts.bind(1, t.id);
    while (ts.step()) t.tumor_outcomes.push_back(decode_tumor_outcome(SqliteRow{ts}, 0));
    ts.reset();
    mk.bind(1, t.id);
    while (mk.step()) t.marks.push_back(decode_mark(SqliteRow{mk}, 0));
    mk.reset();
  }
  return trials;
}

SqliteTrialStore open_sqlite_trial_store_for_reading(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(file.string(), "file", "an existing palprig trial database");
  }
  return SqliteTrialStore(file, TrialStore::Access::read_only);
}

}  // namespace palprig
