#pragma once
// Readers pay PRAGMA quick_check once per state of a database file, not at every open.
//
// quick_check reads every page (on a 1,000,000-trial store it was three quarters of
// `palprig stats trials`). A writer runs it at every open (it must never write into a damaged
// file). A reader runs it the first time it meets a file in a given state and remembers that the
// state was sound; a later reader of the same state skips it. A state is the database file's
// and its -wal's (when it holds anything) identity and change marks: device, inode, size, modification time and status
// change time (ctime, in nanoseconds). Any write through the file system changes the ctime,
// which no user can set back (touch and cp -p set the mtime only), so a file damaged, truncated,
// replaced or copied over since it was checked is a new state and is checked again.
//
// Where: $XDG_CACHE_HOME/palprig/sound-stores, else $HOME/.cache/palprig/sound-stores: the
// user's own cache, never the store's folder (readers never write there, and the folder may be
// read-only or shared). One line per state, the most recent kMaxEntries kept, replaced whole by
// rename so concurrent readers never see half a file. No cache folder that can be written (a
// user without a home, a read-only home) means every reader checks, as before.
//
// What a reader no longer catches: damage that reached a checked file without a write through
// the file system (a disk's silent bit rot). SQLite still refuses any page it finds bad when a
// query reads it (SQLITE_CORRUPT, the same one-line refusal).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace palprig {

struct StoreFileState {
  std::string text;  // the identity of the database file and its -wal as one cache line
  bool operator==(const StoreFileState&) const = default;
};

inline constexpr std::size_t kMaxIntegrityCacheEntries = 256;

// The state of `file` now; nullopt when the file cannot be looked at.
std::optional<StoreFileState> store_file_state(const std::filesystem::path& file);

// The cache file, or an empty path when there is no folder to keep it in.
std::filesystem::path integrity_cache_file();

// Whether this state was found sound by an earlier quick_check.
bool known_sound(const StoreFileState& state);

// Records a state found sound. Failures to write the cache are ignored (it is only a cache).
void remember_sound(const StoreFileState& state) noexcept;

}  // namespace palprig
