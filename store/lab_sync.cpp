#include "store/lab_sync.hpp"

#include <filesystem>
#include <functional>
#include <map>

#include "core/input_error.hpp"
#include "store/pg_target.hpp"
#include "store/postgres_schema.hpp"
#include "store/postgres_session_rows.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/sqlite_session_rows.hpp"
#include "store/sqlite_trial_store.hpp"

namespace palprig {

namespace {

struct JournalLink {
  std::string server;
  bool synced = false;
};

std::map<std::int64_t, JournalLink> journal_links(Database& file) {
  std::map<std::int64_t, JournalLink> links;
  if (!has_lab_sessions_table(file)) return links;
  auto q = file.prepare("SELECT session_id, server, synced FROM lab_store_sessions");
  while (q.step()) links[q.integer(0)] = JournalLink{q.is_null(1) ? "" : q.text(1), q.integer(2) != 0};
  return links;
}

// Trials are pushed in batches so a long backlog neither holds one huge transaction nor pays a
// commit per trial.
constexpr std::size_t kPushBatch = 500;

}  // namespace

PushReport push_file_to_server(Database& file, PgConnection& server, const PushOptions& options) {
  PushReport report;
  const std::string server_key = pg_store_identity(server);  // the store, not its address
  const auto links = journal_links(file);
  const auto is_journal_session = [&](std::int64_t id) {
    const auto link = links.find(id);
    return link != links.end() && link->second.server == server_key;
  };
  // A journal's pass looks only at its sessions for this server not yet synced (the pusher
  // runs after every trial; finished sessions cost nothing).
  std::function<bool(std::int64_t)> wanted;
  if (options.journal_only) {
    wanted = [&](std::int64_t id) { return is_journal_session(id) && !links.at(id).synced; };
  }
  // Trainees enrolled in this file (a rig that trained them offline, or a copied file).
  if (const std::vector<SqlRow> trainees = read_sqlite_trainees(file); !trainees.empty()) {
    PgTransaction tx(server);
    pg_write_trainees(server, trainees);
    tx.commit();
  }
  for (LocalSession& local : read_sqlite_sessions(file, options.study, wanted)) {
    const bool journal_session = is_journal_session(local.id);
    ++report.sessions;
    std::int64_t server_id = 0;
    std::int64_t next_position = 0;
    {
      PgTransaction tx(server);
      bool added = false;
      server_id = pg_push_session(server, local.rows, &added);
      report.sessions_added += added ? 1 : 0;
      next_position =
          server.exec("SELECT COALESCE(MAX(position), -1) + 1 FROM trials WHERE session_id = $1", {pg_text(server_id)})
              .integer(0, 0);
      tx.commit();
    }
    const std::vector<TrialRows> trials = read_sqlite_trials(file, local.id, next_position);
    for (std::size_t first = 0; first < trials.size(); first += kPushBatch) {
      const std::size_t n = std::min(kPushBatch, trials.size() - first);
      PgTransaction tx(server);
      report.trials_added += pg_push_trials(server, server_id, std::span<const TrialRows>(trials.data() + first, n));
      tx.commit();
    }
    if (journal_session && options.mark_synced && local.rows.text(kSessionStatus) == "completed") {
      auto mark =
          file.prepare("UPDATE lab_store_sessions SET synced = 1, server_session_id = ?2 WHERE session_id = ?1");
      mark.bind(1, local.id).bind(2, server_id).run();
      ++report.sessions_synced;
    }
  }
  return report;
}

CopyReport copy_study(const std::string& from, const std::string& to, const std::optional<std::string>& study) {
  const bool from_server = is_postgres_location(from), to_server = is_postgres_location(to);
  // URIs are checked first: one with a password in it is refused before it can be quoted.
  const std::optional<PgTarget> from_target = from_server ? std::optional(parse_pg_target(from)) : std::nullopt;
  const std::optional<PgTarget> to_target = to_server ? std::optional(parse_pg_target(to)) : std::nullopt;
  if (from_target && to_target && from_target->describe() == to_target->describe()) {
    throw InputError("command line", "to", "a store other than `from` (both are " + to_target->describe() + ")");
  }
  if (from == to) throw InputError("command line", "to", "a store other than `from` (both are " + to + ")");
  if (!from_server && !to_server) {
    std::error_code ec;
    if (std::filesystem::equivalent(from, to, ec)) {
      throw InputError("command line", "to", "a store other than `from` (both are the file " + to + ")");
    }
  }
  if (!from_server) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(from, ec))
      throw InputError(from, "file", "an existing palprig trial database");
  }
  CopyReport report;
  // Source: sessions with all their trials, one session at a time.
  std::unique_ptr<SqliteTrialStore> sqlite_source;
  std::unique_ptr<PostgresTrialStore> server_source;
  std::vector<std::pair<std::int64_t, SessionRows>> sessions;
  if (from_server) {
    server_source = std::make_unique<PostgresTrialStore>(*from_target, TrialStore::Access::read_only);
    for (ServerSession& s : pg_read_sessions(server_source->connection(), study))
      sessions.emplace_back(s.id, std::move(s.rows));
  } else {
    sqlite_source = std::make_unique<SqliteTrialStore>(from, TrialStore::Access::read_only);
    for (LocalSession& s : read_sqlite_sessions(sqlite_source->database(), study))
      sessions.emplace_back(s.id, std::move(s.rows));
  }
  // Trainees enrolled in the source go with their sessions (their training rows go with each
  // session's rows).
  const std::vector<SqlRow> trainees =
      from_server ? pg_read_trainees(server_source->connection()) : read_sqlite_trainees(sqlite_source->database());
  if (to_server) {
    PostgresTrialStore target(*to_target, TrialStore::Access::read_write);
    if (!trainees.empty()) {
      PgTransaction tx(target.connection());
      pg_write_trainees(target.connection(), trainees);
      tx.commit();
    }
    for (auto& [id, rows] : sessions) {
      rows.trials = from_server ? pg_read_trials(server_source->connection(), id, 0)
                                : read_sqlite_trials(sqlite_source->database(), id, 0);
      PgTransaction tx(target.connection());
      bool added = false;
      const std::int64_t server_id = pg_push_session(target.connection(), rows, &added);
      const int trials = pg_push_trials(target.connection(), server_id, rows.trials);
      tx.commit();
      ++report.sessions;
      report.sessions_added += added ? 1 : 0;
      report.trials_added += trials;
      rows.trials.clear();
    }
  } else {
    // Each session goes in one transaction, so a copy stopped by a full disk leaves the target a
    // sound store of whole sessions (and the command fails, naming the file and the cause; run
    // again, it goes on where it stopped). A target this copy created is removed instead: a new
    // file holding some of the sessions would look like the whole study.
    std::error_code ec;
    const bool created = !std::filesystem::exists(to, ec);
    try {
      SqliteTrialStore target(to, TrialStore::Access::read_write);
      if (!trainees.empty()) {
        Transaction tx(target.database());
        write_sqlite_trainees(target.database(), trainees);
        tx.commit();
      }
      for (auto& [id, rows] : sessions) {
        rows.trials = from_server ? pg_read_trials(server_source->connection(), id, 0)
                                  : read_sqlite_trials(sqlite_source->database(), id, 0);
        const SqliteWriteResult written = write_sqlite_session(target.database(), rows);
        ++report.sessions;
        report.sessions_added += written.session_added ? 1 : 0;
        report.trials_added += written.trials_added;
        rows.trials.clear();
      }
    } catch (...) {
      if (created) {
        for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(to + suffix, ec);
      }
      throw;
    }
  }
  return report;
}

}  // namespace palprig
