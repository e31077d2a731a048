#pragma once
// Moving sessions between an SQLite trial file and the lab's PostgreSQL server.
//
//   push_file_to_server   the pending trials of a file (a bench's journal, or any palprig file)
//                         onto the server: each session found by its global identity, only the
//                         trials the server does not have, one transaction per session. The
//                         journal's pusher and `palprig store sync` run it.
//   copy_study            `palprig store copy`: a study (or everything) from one store to
//                         another, SQLite or PostgreSQL either way.
// Both are idempotent: running them twice stores every session and trial once.
#include <cstdint>
#include <optional>
#include <string>

#include "store/pg_connection.hpp"
#include "store/sqlite_db.hpp"

namespace palprig {

struct PushReport {
  int sessions = 0;        // sessions looked at
  int sessions_added = 0;  // new on the server
  int trials_added = 0;
  int sessions_synced = 0;  // journal sessions now complete on the server (marked, pushed no more)
};

struct PushOptions {
  std::optional<std::string> study;  // protocol name; all when empty
  bool journal_only = false;         // only sessions of this file's journal for this server, not yet synced
  bool mark_synced = false;          // the file is writable: mark journal sessions done
};

PushReport push_file_to_server(Database& file, PgConnection& server, const PushOptions& options);

struct CopyReport {
  int sessions = 0, sessions_added = 0, trials_added = 0;
};

// `from` and `to` are store locations (file paths or postgresql:// URIs). The source is only
// read; the target is created when missing (its schema too). Throws InputError for a missing
// or foreign source, an unreachable server, or from == to.
CopyReport copy_study(const std::string& from, const std::string& to, const std::optional<std::string>& study);

}  // namespace palprig
