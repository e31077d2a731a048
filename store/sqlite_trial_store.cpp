#include "store/sqlite_trial_store.hpp"

// The SQLite trial store: opening (with the checks of sqlite_schema.cpp), participants,
// sessions and trial writes, one transaction per trial. The lock is sqlite_session_lock.cpp,
// the reads for stats and export sqlite_trial_scans.cpp.
#include <sqlite3.h>

#include <cmath>
#include <optional>

#include "core/input_error.hpp"
#include "store/sqlite_session_rows.hpp"
#include "store/trial_rows.hpp"
#include "store/utc_time.hpp"

namespace palprig {

namespace {

std::optional<double> finite_or_null(double x) {
  if (std::isfinite(x)) return x;
  return std::nullopt;
}

}  // namespace

namespace {

// A store is a file SQLite can lock, grow and put a -wal beside: a device (/dev/full) or a FIFO
// given as one is refused before SQLite touches it.
const std::filesystem::path& regular_or_new(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(file.string(), "file",
                     "a trial database: a regular file or a new path (this is a device, FIFO or folder)");
  return file;
}

}  // namespace

SqliteTrialStore::SqliteTrialStore(const std::filesystem::path& file, Access access) try
    : db_(regular_or_new(file),
          access == Access::read_only ? Database::Mode::read_only : Database::Mode::read_write_create) {
  if (access == Access::read_write) create_schema_if_blank();
  check_identity();
  // Scans of large stores (stats, export, and quick_check below) read through a memory map
  // instead of copying pages.
  db_.exec("PRAGMA mmap_size = 1073741824");
  // Never write into a damaged file (a new session in it could be lost with the rest, and
  // SQLite may make the damage worse), and never compute statistics or exports from one (the
  // trials on bad pages would silently be missing). Readers skip a file state already found
  // sound (store/integrity_check_cache.hpp).
  db_.refuse_if_damaged();
  if (access == Access::read_write) migrate_if_older();
  trial_columns_ = sqlite_trial_column_count(db_);
  if (access == Access::read_write) create_lock_table();
  if (access == Access::read_write) {
    // WAL: readers never block the writer; synchronous FULL: a committed trial survives a
    // crash of the process and of the machine.
    db_.exec_waiting("PRAGMA journal_mode = WAL");
    db_.exec("PRAGMA synchronous = FULL; PRAGMA foreign_keys = ON;");
  }
} catch (const SqliteError& e) {
  // Whatever the member initialiser or the checks threw, the file was the problem.
  if (e.code() == SQLITE_NOTADB) {
    throw InputError(file.string(), "file", "a palprig trial database (this is not an SQLite database)");
  }
  // Opening, creating or migrating a store writes none of its trials: a read-only file or
  // folder, a full disk, is one line naming the file and the cause, exit 2.
  if (access == Access::read_write && (e.environment() || e.code() == SQLITE_CANTOPEN)) {
    std::string cause = sqlite_environment_cause(file.string(), e.code(), e.system_errno());
    throw InputError(file.string(), "file",
                     "a trial database palprig can open and write (" + (cause.empty() ? std::string(e.what()) : cause) +
                         "; nothing was written)");
  }
  // A reader writes nothing, ever: what kept it from reading is the file's or the machine's.
  if (access == Access::read_only && e.code() == SQLITE_CANTOPEN) {
    std::string cause = sqlite_environment_cause(file.string(), e.code(), e.system_errno());
    throw InputError(
        file.string(), "file",
        "a trial database palprig can open and read (" + (cause.empty() ? std::string(e.what()) : cause) + ")");
  }
  throw;
}

SqliteTrialStore::~SqliteTrialStore() {
  const std::vector<std::int64_t> held = held_;  // release_session edits held_
  for (std::int64_t session_id : held) {
    try {
      release_session(session_id);
    } catch (...) {
      // A database gone bad on the way out: the lock row names a dead process, which the next
      // claim recognises as stale.
    }
  }
}

std::optional<ParticipantRecord> SqliteTrialStore::find_participant(const std::string& code) {
  auto s = db_.prepare("SELECT id, code, number, simulated FROM participants WHERE code = ?1");
  s.bind(1, code);
  if (!s.step()) return std::nullopt;
  return ParticipantRecord{s.integer(0), s.text(1), static_cast<int>(s.integer(2)), s.integer(3) != 0};
}

ParticipantRecord SqliteTrialStore::enrol(const std::string& code, bool simulated) {
  if (auto p = find_participant(code)) return *p;
  Transaction tx(db_);
  // Another process may have enrolled the same code between the look-up and the write lock.
  if (auto p = find_participant(code)) return *p;
  auto next = db_.prepare("SELECT COALESCE(MAX(number), 0) + 1 FROM participants");
  next.step();
  const int number = static_cast<int>(next.integer(0));
  auto ins = db_.prepare("INSERT INTO participants (code, number, simulated, created_utc) VALUES (?1, ?2, ?3, ?4)");
  ins.bind(1, code).bind(2, number).bind(3, simulated ? 1 : 0).bind(4, utc_now_text()).run();
  const std::int64_t id = db_.last_insert_rowid();
  tx.commit();
  return ParticipantRecord{id, code, number, simulated};
}

std::optional<std::int64_t> SqliteTrialStore::find_unfinished_session(const ParticipantRecord& who,
                                                                      const std::string& protocol_name) {
  auto s = db_.prepare(
      "SELECT id FROM sessions WHERE participant_id = ?1 AND protocol_name = ?2 AND status = 'running' "
      "ORDER BY id DESC LIMIT 1");
  s.bind(1, who.id).bind(2, protocol_name);
  if (!s.step()) return std::nullopt;
  return s.integer(0);
}

std::int64_t SqliteTrialStore::insert_session_row(const ParticipantRecord& who, const TaskSessionRow& row,
                                                  const SessionSetup& setup) {
  // Under the write lock: another process may have started this participant's session since
  // the caller looked for an unfinished one (the same participant started twice at once).
  {
    auto running = db_.prepare(
        "SELECT id FROM sessions WHERE participant_id = ?1 AND protocol_name = ?2 AND status = 'running' "
        "ORDER BY id DESC LIMIT 1");
    running.bind(1, who.id).bind(2, row.protocol_name);
    if (running.step()) {
      const std::int64_t other = running.integer(0);
      const std::string name = "participant '" + who.code + "'";
      refuse_if_held_elsewhere(other, name);
      throw InputError(db_.file(), name,
                       "already has an unfinished session with protocol '" + row.protocol_name + "' (session " +
                           std::to_string(other) + "); to continue it, run the same command again with --resume");
    }
  }
  auto ins = db_.prepare(
      "INSERT INTO sessions (participant_id, protocol_name, task, bids_task, protocol_json, protocol_dir, seed, "
      "condition_order, rig_id, rig_backend, calibration, participant_model, status, started_utc) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, 'running', ?13)");
  ins.bind(1, who.id)
      .bind(2, row.protocol_name)
      .bind(3, row.task)
      .bind(4, row.bids_task)
      .bind(5, row.protocol_snapshot.dump())
      .bind(6, setup.protocol_dir)
      .bind(7, static_cast<std::int64_t>(row.seed))  // stored as the same 64 bits
      .bind(8, row.condition_order.dump())
      .bind(9, setup.rig_id)
      .bind(10, setup.rig_backend)
      .bind(11, setup.calibration);
  if (setup.participant_model.is_null())
    ins.bind_null(12);
  else
    ins.bind(12, setup.participant_model.dump());
  ins.bind(13, utc_now_text()).run();
  return db_.last_insert_rowid();
}

std::int64_t SqliteTrialStore::create_task_session(const ParticipantRecord& who, const TaskSessionRow& row,
                                                   const SessionSetup& setup) {
  Transaction tx(db_);
  const std::int64_t session_id = insert_session_row(who, row, setup);
  write_lock_row(session_id);
  tx.commit();
  return session_id;
}

StoredTaskSession SqliteTrialStore::load_task_session(std::int64_t session_id, const std::string& task,
                                                      const std::string& trial_table) {
  auto q = db_.prepare(
      "SELECT s.id, s.protocol_json, s.protocol_dir, s.seed, s.status, p.id, p.code, p.number, p.simulated, s.task "
      "FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = ?1");
  q.bind(1, session_id);
  const std::string which = "session " + std::to_string(session_id);
  if (!q.step()) throw InputError(db_.file(), which, "an existing " + task + " session");
  if (q.text(9) != task) throw InputError(db_.file(), which, "a " + task + " session, got task " + q.text(9));
  StoredTaskSession s;
  s.id = q.integer(0);
  s.protocol_snapshot = nlohmann::json::parse(q.text(1));
  s.protocol_dir = q.text(2);
  s.seed = static_cast<std::uint64_t>(q.integer(3));
  s.status = q.text(4);
  s.participant = ParticipantRecord{q.integer(5), q.text(6), static_cast<int>(q.integer(7)), q.integer(8) != 0};
  // trial_table is one of the store's own table names (threshold_trials, pulse_trials), never user text.
  auto done =
      db_.prepare("SELECT count(*), COALESCE(MAX(position), -1) FROM " + trial_table + " WHERE session_id = ?1");
  done.bind(1, session_id);
  done.step();
  s.completed_trials = static_cast<int>(done.integer(0));
  if (done.integer(1) != s.completed_trials - 1) {
    throw InputError(db_.file(), which,
                     task + " trials committed in order (positions are missing; the database was edited)");
  }
  return s;
}

std::int64_t SqliteTrialStore::create_session(const ParticipantRecord& who, const Protocol& protocol,
                                              const SessionPlan& plan, const SessionSetup& setup) {
  Transaction tx(db_);
  const TaskSessionRow row{to_string(protocol.task), protocol.name, protocol.bids_task,
                           protocol.snapshot,        plan.seed,     nlohmann::json(plan.condition_order)};
  const std::int64_t session_id = insert_session_row(who, row, setup);

  auto planned = db_.prepare(
      "INSERT INTO planned_trials (session_id, position, block, condition_index, condition, practice, combination, "
      "break_after) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
  for (const PlannedTrial& t : plan.trials) {
    planned.bind(1, session_id)
        .bind(2, t.position)
        .bind(3, t.block)
        .bind(4, t.condition)
        .bind(5, protocol.conditions.at(static_cast<std::size_t>(t.condition)).name)
        .bind(6, t.practice ? 1 : 0)
        .bind(7, t.combination)
        .bind(8, t.break_after ? 1 : 0)
        .run();
  }
  write_lock_row(session_id);
  tx.commit();
  return session_id;
}

StoredSession SqliteTrialStore::load_session(std::int64_t session_id) {
  StoredSession s;
  auto q = db_.prepare(
      "SELECT s.id, s.protocol_json, s.protocol_dir, s.status, s.seed, s.condition_order, p.id, p.code, p.number, "
      "p.simulated FROM sessions s JOIN participants p ON p.id = s.participant_id WHERE s.id = ?1");
  q.bind(1, session_id);
  if (!q.step()) throw InputError(db_.file(), "session " + std::to_string(session_id), "an existing session");
  s.id = q.integer(0);
  s.protocol_snapshot = nlohmann::json::parse(q.text(1));
  s.protocol_dir = q.text(2);
  s.status = q.text(3);
  s.plan.seed = static_cast<std::uint64_t>(q.integer(4));
  s.plan.condition_order = nlohmann::json::parse(q.text(5)).get<std::vector<int>>();
  s.participant = ParticipantRecord{q.integer(6), q.text(7), static_cast<int>(q.integer(8)), q.integer(9) != 0};
  s.plan.participant_number = s.participant.number;

  auto t = db_.prepare(
      "SELECT position, block, condition_index, practice, combination, break_after FROM planned_trials "
      "WHERE session_id = ?1 ORDER BY position");
  t.bind(1, session_id);
  while (t.step()) {
    s.plan.trials.push_back(PlannedTrial{static_cast<int>(t.integer(0)), static_cast<int>(t.integer(1)),
                                         static_cast<int>(t.integer(2)), t.integer(3) != 0,
                                         static_cast<int>(t.integer(4)), t.integer(5) != 0});
  }
  auto done = db_.prepare("SELECT count(*), COALESCE(MAX(position), -1) FROM trials WHERE session_id = ?1");
  done.bind(1, session_id);
  done.step();
  s.completed_trials = static_cast<int>(done.integer(0));
  // Trials are committed in order, so the committed ones are exactly positions 0..n-1.
  if (done.integer(1) != s.completed_trials - 1) {
    throw InputError(db_.file(), "session " + std::to_string(session_id),
                     "trials committed in order (positions are missing; the database was edited)");
  }
  return s;
}

void SqliteTrialStore::complete_session(std::int64_t session_id) {
  Transaction tx(db_);
  auto u = db_.prepare("UPDATE sessions SET status = 'completed', finished_utc = ?2 WHERE id = ?1");
  u.bind(1, session_id).bind(2, utc_now_text()).run();
  auto del = db_.prepare("DELETE FROM session_locks WHERE session_id = ?1");
  del.bind(1, session_id).run();
  tx.commit();
  held_.erase(std::remove(held_.begin(), held_.end(), session_id), held_.end());
}

void SqliteTrialStore::insert_trial(std::int64_t session_id, const TrialRecord& r) {
  const bool discrimination = r.mode != PresentationMode::scene;
  if (!insert_trial_) {
    insert_trial_ = std::make_unique<Statement>(
        db_,
        "INSERT INTO trials (session_id, position, block, condition, mode, practice, combination, combination_label, "
        "stimulus1_kPa, stimulus2_kPa, stimulus3_kPa, truth, answered, answer, response_time_s, onset_s, felt1_kPa, "
        "felt2_kPa, felt3_kPa, outcome1, outcome2, outcome3, false_marks, completed_utc, confidence, stimulus_end_s, "
        "stimulus_reached_s, case_name, case_seed, case_difficulty, case_tumors) "
        "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17, ?18, ?19, ?20, ?21, ?22, "
        "?23, ?24, ?25, ?26, ?27, ?28, ?29, ?30, ?31)");
  }
  Statement& ins = *insert_trial_;
  ins.bind(1, session_id)
      .bind(2, r.planned.position)
      .bind(3, r.planned.block)
      .bind(4, r.condition)
      .bind(5, to_string(r.mode))
      .bind(6, r.planned.practice ? 1 : 0)
      .bind(7, r.planned.combination)
      .bind(13, r.answered ? 1 : 0)
      .bind(16, r.onset_s)
      .bind(24, utc_now_text());
  if (auto end = finite_or_null(r.stimulus_end_s)) ins.bind(26, *end);
  if (auto reached = finite_or_null(r.stimulus_reached_s)) ins.bind(27, *reached);
  if (r.answered && r.confidence) ins.bind(25, static_cast<std::int64_t>(*r.confidence));
  if (!discrimination && !r.case_name.empty()) {  // a case named by the runner (not a hand-made record)
    ins.bind(28, r.case_name);
    if (r.case_seed) ins.bind(29, static_cast<std::int64_t>(*r.case_seed));
    if (r.case_difficulty) ins.bind(30, std::string(to_string(*r.case_difficulty)));
    ins.bind(31, r.case_tumors);
  }
  if (discrimination) {
    ins.bind(8, r.combination_label);
    for (int f = 0; f < kFingerCount; ++f) ins.bind(9 + f, r.stimulus_kPa[static_cast<std::size_t>(f)]);
    ins.bind(12, trial_rows::flags_text(r.truth));
  }
  for (int f = 0; f < kFingerCount; ++f) ins.bind(17 + f, finite_or_null(r.felt_kPa[static_cast<std::size_t>(f)]));
  if (r.answered) {
    ins.bind(15, r.response_time_s);
    if (discrimination) {
      ins.bind(14, trial_rows::flags_text(r.answer));
      for (int f = 0; f < kFingerCount; ++f)
        ins.bind(20 + f, to_string(r.finger_outcomes[static_cast<std::size_t>(f)]));
    } else {
      ins.bind(23, r.localisation.false_marks);
    }
  }
  ins.run();
  const std::int64_t trial_id = db_.last_insert_rowid();
  if (!discrimination && r.answered) {
    auto ts =
        db_.prepare("INSERT INTO tumor_scores (trial_id, tumor, outcome, nearest_mark_mm) VALUES (?1, ?2, ?3, ?4)");
    for (const TumorScore& score : r.localisation.tumors) {
      ts.bind(1, trial_id).bind(2, score.tumor).bind(3, score.hit ? "TP" : "FN");
      if (score.nearest_mark_mm >= 0) ts.bind(4, score.nearest_mark_mm);
      ts.run();
    }
    auto mk = db_.prepare("INSERT INTO marks (trial_id, mark, x_mm, y_mm, tumor) VALUES (?1, ?2, ?3, ?4, ?5)");
    for (std::size_t i = 0; i < r.marks.size(); ++i) {
      mk.bind(1, trial_id).bind(2, static_cast<std::int64_t>(i)).bind(3, r.marks[i].x_mm).bind(4, r.marks[i].y_mm);
      const int hit = i < r.localisation.mark_tumor.size() ? r.localisation.mark_tumor[i] : -1;
      if (hit >= 0) mk.bind(5, r.localisation.tumors[static_cast<std::size_t>(hit)].tumor);
      mk.run();
    }
  }
}

void SqliteTrialStore::commit_trial(std::int64_t session_id, const TrialRecord& trial) {
  Transaction tx(db_);
  insert_trial(session_id, trial);
  tx.commit();
}

void SqliteTrialStore::commit_trials(std::int64_t session_id, std::span<const TrialRecord> trials) {
  Transaction tx(db_);
  for (const TrialRecord& t : trials) insert_trial(session_id, t);
  tx.commit();
}

}  // namespace palprig
