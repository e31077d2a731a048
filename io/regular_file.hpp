#pragma once
// The one door through which palprig reads an outside file: it must be a regular file no larger
// than its reader's bound. A FIFO would block the reader for ever, /dev/zero or a 3 GiB sparse
// file would be read until memory runs out, a directory gives the library's raw text; each is
// refused with one palprig line (InputError: the file, "file", "a regular file of at most N MiB
// holding <what>, got <what it is>") before a byte is read. Every floor's readers (formats,
// statistics, inputs, controller, calibration, store) share it.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace palprig {

inline constexpr std::uintmax_t kMiB = std::uintmax_t(1) << 20;

// The bounds of the readers (docs/developing.md, "Hardening notes").
inline constexpr std::uintmax_t kMaxJsonFileBytes = 16 * kMiB;        // rig, scene, calibration, protocol files
inline constexpr std::uintmax_t kMaxMapFileBytes = 256 * kMiB;        // stiffness map CSV and PGM
inline constexpr std::uintmax_t kMaxTraceFileBytes = 256 * kMiB;      // pen trace CSV (1 h at 1 kHz is ~150 MiB)
inline constexpr std::uintmax_t kMaxTableFileBytes = 64 * kMiB;       // statistics and calibration CSV tables
inline constexpr std::uintmax_t kMaxRecordingFileBytes = 512 * kMiB;  // evemu recordings
inline constexpr std::uintmax_t kMaxTelemetryFileBytes = std::uintmax_t(4) << 30;  // what the writer may write

// "16 MiB", "512 KiB" or "100 bytes".
std::string file_size_text(std::uintmax_t bytes);

// "" when `path` is a regular file of at most max_bytes (symbolic links followed); otherwise
// what it is instead: "a FIFO", "a directory", "a device", "a socket", "3221225472 bytes",
// "no such file", or the system's reason it cannot be read. Opens nothing that is not a
// regular file, so a FIFO never blocks.
std::string regular_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes);

// The whole of `path`, read through one descriptor that was checked to be a regular file of
// at most max_bytes (a file that grows past the bound while it is read is refused too).
// Throws InputError(path, "file", "a regular file of at most <max> holding <what>, got ...").
std::string read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what);

// The same check, then `path` opened as a stream for readers that go line by line or record by
// record (opened by name after the check: a file swapped for a FIFO between the two is a race
// the caller accepts).
std::ifstream open_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what,
                                std::ios::openmode mode = std::ios::in | std::ios::binary);

}  // namespace palprig
