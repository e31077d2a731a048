#include "store/sqlite_trial_store.hpp"

// The SQLite store's training tables (schema 5): trainees enrolled in curricula, their training
// sessions and the cases each was given. The rows themselves are written by the one writer
// store copy and pushes use too (store/sqlite_session_rows.cpp), so a session's training row is
// the same wherever it goes.
#include "store/sqlite_session_rows.hpp"
#include "store/training_rows.hpp"
#include "store/utc_time.hpp"

namespace palprig {

void SqliteTrialStore::enrol_trainee(const std::string& code, const std::string& curriculum) {
  Transaction tx(db_);
  write_sqlite_trainees(db_, {SqlRow{code, curriculum, utc_now_text()}});
  tx.commit();
}

std::vector<TraineeRecord> SqliteTrialStore::trainees() {
  std::vector<TraineeRecord> out;
  for (const SqlRow& row : read_sqlite_trainees(db_)) {
    out.push_back({std::get<std::string>(row[0]), std::get<std::string>(row[1]), std::get<std::string>(row[2])});
  }
  return out;
}

std::vector<TrainingSessionRecord> SqliteTrialStore::training_sessions(const std::string& trainee) {
  std::vector<TrainingSessionRecord> out;
  if (!has_training_tables(db_)) return out;
  auto q = db_.prepare("SELECT session_id FROM training_sessions WHERE trainee = ?1 ORDER BY started_utc, session_id");
  q.bind(1, trainee);
  std::vector<std::int64_t> ids;
  while (q.step()) ids.push_back(q.integer(0));
  for (std::int64_t id : ids) {
    if (const auto row = read_sqlite_training_row(db_, id)) out.push_back(training_record_of(id, *row));
  }
  return out;
}

void SqliteTrialStore::begin_training_session(const TrainingSessionRecord& record) {
  Transaction tx(db_);
  TrainingSessionRecord r = record;
  if (r.started_utc.empty()) r.started_utc = utc_now_text();
  write_sqlite_training_row(db_, r.session_id, training_row_of(r), true);
  tx.commit();
}

void SqliteTrialStore::complete_training_session(std::int64_t session_id, const nlohmann::json& scores,
                                                 bool met_benchmark) {
  Transaction tx(db_);
  auto done = db_.prepare(
      "UPDATE training_sessions SET status = 'completed', scores = ?2, met_benchmark = ?3, finished_utc = ?4 "
      "WHERE session_id = ?1");
  done.bind(1, session_id).bind(2, scores.dump()).bind(3, met_benchmark ? 1 : 0).bind(4, utc_now_text()).run();
  tx.commit();
}

}  // namespace palprig
