// palprig store: moving trials between a bench's SQLite files and the lab's PostgreSQL server.
//   palprig store sync --from JOURNAL --to postgresql://...   push what the server lacks
//   palprig store copy --from A --to B [--study NAME]          copy a study, SQLite <-> PostgreSQL
// Both are idempotent (running them twice stores every trial once).
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "core/input_error.hpp"
#include "store/lab_sync.hpp"
#include "store/pg_target.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/sqlite_trial_store.hpp"

using namespace palprig;

namespace {

void register_sync(CLI::App* store) {
  struct Args {
    std::string from, to, study;
  };
  auto a = std::make_shared<Args>();
  auto* sub = store->add_subcommand(
      "sync",
      "Push the trials of a bench's journal (or any palprig SQLite file) that the lab server does not have yet; "
      "sessions are matched by their global id, trials by position, so pushing twice stores once");
  sub->add_option("--from", a->from, "The journal or trial file (SQLite)")->required();
  sub->add_option("--to", a->to,
                  "The lab server: postgresql://user@host:port/dbname (password from PGPASSWORD or ~/.pgpass)")
      ->required();
  sub->add_option("--study", a->study, "Only the sessions of this protocol name");
  sub->callback([a] {
    if (is_postgres_location(a->from)) {
      throw InputError("command line", "from",
                       "a journal or trial file (SQLite), not a server (" + parse_pg_target(a->from).describe() + ")");
    }
    if (!is_postgres_location(a->to)) {
      throw InputError("command line", "to", "a postgresql:// URI of the lab server (got the file " + a->to + ")");
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(a->from, ec))
      throw InputError(a->from, "file", "an existing palprig trial database");
    SqliteTrialStore file(a->from, TrialStore::Access::read_write);
    PostgresTrialStore server(parse_pg_target(a->to), TrialStore::Access::read_write);
    PushOptions options;
    if (!a->study.empty()) options.study = a->study;
    options.mark_synced = true;
    const PushReport r = push_file_to_server(file.database(), server.connection(), options);
    std::cout << "palprig store sync: " << r.sessions << " sessions (" << r.sessions_added << " new on the server), "
              << r.trials_added << " trials pushed to " << server.target().describe() << "\n";
  });
}

void register_copy(CLI::App* store) {
  struct Args {
    std::string from, to, study;
  };
  auto a = std::make_shared<Args>();
  auto* sub = store->add_subcommand(
      "copy",
      "Copy a study (or every session) between trial stores: SQLite file to PostgreSQL server or back "
      "(the target is created when missing; what is already there is kept, nothing is stored twice)");
  sub->add_option("--from", a->from, "Source: SQLite file or postgresql://user@host:port/dbname")->required();
  sub->add_option("--to", a->to, "Target: SQLite file or postgresql://user@host:port/dbname")->required();
  sub->add_option("--study", a->study, "Only the sessions of this protocol name");
  sub->callback([a] {
    const CopyReport r =
        copy_study(a->from, a->to, a->study.empty() ? std::nullopt : std::optional<std::string>(a->study));
    std::cout << "palprig store copy: " << r.sessions << " sessions (" << r.sessions_added << " new), "
              << r.trials_added << " trials copied\n";
  });
}

}  // namespace

void register_store_command(CLI::App& app) {
  auto* store = app.add_subcommand(
      "store", "Move trials between SQLite files and the lab's PostgreSQL server (sync a journal, copy a study)");
  store->require_subcommand(1);
  register_sync(store);
  register_copy(store);
}
