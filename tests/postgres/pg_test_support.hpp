#pragma once
// What the PostgreSQL tests share: the server started for them by with_server.sh
// (pg_virtualenv: PGHOST, PGPORT, PGUSER, PGPASSWORD set), a fresh database per test, and
// stopping and starting that server mid-test.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "store/pg_connection.hpp"
#include "store/pg_target.hpp"
#include "store/postgres_schema.hpp"
#include "store/postgres_session_rows.hpp"
#include "store/sqlite_db.hpp"
#include "store/sqlite_session_rows.hpp"

namespace palprig::testing {

// Skips the test, with the reason, when no server could be started for it.
#define PALPRIG_REQUIRE_PG_SERVER()                                                           \
  do {                                                                                        \
    if (const char* reason = std::getenv("PALPRIG_PG_SKIP")) GTEST_SKIP() << reason;          \
    if (!std::getenv("PGPORT")) GTEST_SKIP() << "PGPORT not set: run through with_server.sh"; \
  } while (0)

inline std::string env_or(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

// postgresql://user@host:port/dbname; the password stays in PGPASSWORD.
inline std::string pg_uri(const std::string& dbname) {
  return "postgresql://" + env_or("PGUSER", "postgres") + "@" + env_or("PGHOST", "localhost") + ":" +
         env_or("PGPORT", "5432") + "/" + dbname;
}

// A new empty database on the test server; returns its URI.
inline std::string fresh_database(const std::string& name) {
  PgConnection admin(parse_pg_target(pg_uri("postgres")));
  admin.exec("DROP DATABASE IF EXISTS " + name);
  admin.exec("CREATE DATABASE " + name);
  return pg_uri(name);
}

// pg_ctl stop / start of the throwaway cluster (pg_ctlcluster wraps pg_ctl for Debian clusters).
inline int server_ctl(const std::string& action) {
  const std::string cmd = "pg_ctlcluster " + env_or("PGVERSION", "15") + " regress " + action + " >/dev/null 2>&1";
  return std::system(cmd.c_str());
}

inline std::int64_t pg_scalar(const std::string& uri, const std::string& sql) {
  PgConnection c(parse_pg_target(uri));
  return c.exec(sql).integer(0, 0);
}

// A server an older palprig made: a fresh database at PostgreSQL schema `version`, holding every
// session and trial of the SQLite file `bench_file` as that version's push leaves them (the
// columns it has no place for left out). Returns its URI. The migration suites start here.
inline std::string old_server_holding(const std::string& name, int version, const std::string& bench_file) {
  std::string uri = fresh_database(name);
  PgConnection server(parse_pg_target(uri));
  ensure_pg_schema(server, version);
  Database bench(bench_file, Database::Mode::read_only);
  PgTransaction tx(server);
  for (const LocalSession& s : read_sqlite_sessions(bench, std::nullopt))
    pg_push_trials(server, pg_push_session(server, s.rows), read_sqlite_trials(bench, s.id, 0));
  tx.commit();
  return uri;
}

}  // namespace palprig::testing
