// open_trial_store: the one place that maps a store location to its implementation.
#include <filesystem>

#include "core/input_error.hpp"
#include "store/journaled_trial_store.hpp"
#include "store/pg_target.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_store.hpp"

namespace palprig {

bool is_server_store_location(std::string_view location) noexcept {
  return location.starts_with("postgresql://") || location.starts_with("postgres://");
}

std::unique_ptr<TrialStore> open_trial_store(const std::string& location, TrialStore::Access access) {
  if (is_server_store_location(location)) {
    const PgTarget target = parse_pg_target(location);
    // Readers (stats, export) read the server; a session writes through the bench's journal
    // (offline first, store/journaled_trial_store.hpp).
    if (access == TrialStore::Access::read_only) return std::make_unique<PostgresTrialStore>(target, access);
    return std::make_unique<JournaledTrialStore>(target, default_journal_file());
  }
  const std::filesystem::path file(location);
  if (access == TrialStore::Access::read_only) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
      throw InputError(file.string(), "file", "an existing palprig trial database");
    }
  }
  return std::make_unique<SqliteTrialStore>(file, access);
}

}  // namespace palprig
