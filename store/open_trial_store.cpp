// open_trial_store: the one place that maps a store location to its implementation.
#include <filesystem>

#include "models/parse_error.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/trial_store.hpp"

namespace palprig {

bool is_server_store_location(std::string_view location) noexcept {
  return location.starts_with("postgresql://") || location.starts_with("postgres://");
}

std::unique_ptr<TrialStore> open_trial_store(const std::string& location, TrialStore::Access access) {
  if (is_server_store_location(location)) {
    throw InputError(location, "location",
                     "an SQLite file path (this palprig was built without the PostgreSQL store)");
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
