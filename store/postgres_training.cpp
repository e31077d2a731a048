#include "store/postgres_trial_store.hpp"

// The lab server's training tables (schema 6), written with the same row functions as the
// pushes and copies (store/postgres_session_rows.cpp): a trainee's enrolment and history are on
// the server, so the trainee trains on any rig of the lab.
#include "store/postgres_session_rows.hpp"
#include "store/training_rows.hpp"
#include "store/utc_time.hpp"

namespace palprig {

void PostgresTrialStore::enrol_trainee(const std::string& code, const std::string& curriculum) {
  PgTransaction tx(db_);
  pg_write_trainees(db_, {SqlRow{code, curriculum, utc_now_text()}});
  tx.commit();
}

std::vector<TraineeRecord> PostgresTrialStore::trainees() {
  std::vector<TraineeRecord> out;
  for (const SqlRow& row : pg_read_trainees(db_)) {
    out.push_back({std::get<std::string>(row[0]), std::get<std::string>(row[1]), std::get<std::string>(row[2])});
  }
  return out;
}

std::vector<TrainingSessionRecord> PostgresTrialStore::training_sessions(const std::string& trainee) {
  std::vector<TrainingSessionRecord> out;
  if (!pg_has_training_tables(db_)) return out;
  const PgResult r = db_.exec("SELECT session_id, " + column_list(kTrainingColumns) +
                                  " FROM training_sessions WHERE trainee = $1 ORDER BY started_utc, session_id",
                              {trainee});
  for (int i = 0; i < r.rows(); ++i) {
    SqlRow row;
    for (std::size_t c = 0; c < kTrainingColumns.size(); ++c) {
      const int column = static_cast<int>(c) + 1;
      if (r.is_null(i, column))
        row.emplace_back(std::monostate{});
      else if (kTrainingColumns[c].type == 'i')
        row.emplace_back(r.integer(i, column));
      else
        row.emplace_back(r.text(i, column));
    }
    out.push_back(training_record_of(r.integer(i, 0), row));
  }
  return out;
}

void PostgresTrialStore::begin_training_session(const TrainingSessionRecord& record) {
  PgTransaction tx(db_);
  TrainingSessionRecord r = record;
  if (r.started_utc.empty()) r.started_utc = utc_now_text();
  pg_write_training_row(db_, r.session_id, training_row_of(r), true);
  tx.commit();
}

void PostgresTrialStore::complete_training_session(std::int64_t session_id, const nlohmann::json& scores,
                                                   bool met_benchmark) {
  db_.exec(
      "UPDATE training_sessions SET status = 'completed', scores = $2, met_benchmark = $3, finished_utc = $4 "
      "WHERE session_id = $1",
      {pg_text(session_id), scores.dump(), std::string(met_benchmark ? "1" : "0"), utc_now_text()});
}

}  // namespace palprig
