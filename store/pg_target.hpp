#pragma once
// Where a PostgreSQL trial store lives: a connection URI (postgresql://user@host:port/dbname)
// checked by libpq's own parser, with what libpq will use once the environment (PGHOST,
// PGPORT, PGDATABASE, PGUSER, ...) has filled the gaps. A password is refused in the URI (it
// would sit in the shell history and the process list): PGPASSWORD or ~/.pgpass carry it. No
// message built here ever contains a password.
#include <string>

namespace palprig {

struct PgTarget {
  std::string conninfo;  // the URI as given (holds no password)
  std::string host, port, dbname, user;

  // "host localhost port 5433 database lab" for messages.
  std::string describe() const;
};

// Does this store location name a PostgreSQL server rather than an SQLite file?
bool is_postgres_location(const std::string& location);

// Parses and checks a URI; throws InputError(uri, field, expected) on a malformed URI (with
// libpq's reason) or a password in it.
PgTarget parse_pg_target(const std::string& uri);

}  // namespace palprig
