#pragma once
// Telemetry leaves the loop through a lock-free single-producer/single-consumer queue
// (Boost.Lockfree) and is written by its own thread, as CSV or as a compact binary file
// ("PALPRIGT" magic, version, record size, then raw TelemetryRecord structs, little-endian)
// that `palprig telemetry to-csv` converts.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include <boost/lockfree/spsc_queue.hpp>

#include "controller/telemetry.hpp"

namespace palprig {

// The binary telemetry file's version (its header). 2: the per-finger position, force and vent
// reason after the flags; 3: then how far tissue dragging carries the tissue under
// each finger (drag_x_mm, drag_y_mm).
inline constexpr std::uint32_t kTelemetryFileVersion = 3;

enum class TelemetryFormat { binary, csv };

// Binary when the name ends in .bin or .ptl, CSV otherwise.
TelemetryFormat telemetry_format_for(const std::filesystem::path& path);

// Telemetry stops (the writer fails, the loop faults and vents, the message says why) before it
// fills a disk: a run on a runaway input must not take the machine down with it.
struct TelemetryLimits {
  // Most bytes one file may take. 4 GiB is about 5 hours of CSV or 15 hours of binary at 1 kHz.
  std::uint64_t max_bytes = std::uint64_t(4) << 30;
  // Stop when the disk holding the file has less free space than this (checked every MiB).
  std::uint64_t min_free_bytes = std::uint64_t(512) << 20;
};

class TelemetryWriter {
 public:
  TelemetryWriter(std::filesystem::path path, TelemetryFormat format, std::size_t queue_capacity = 1 << 16,
                  TelemetryLimits limits = {});
  ~TelemetryWriter();
  TelemetryWriter(const TelemetryWriter&) = delete;
  TelemetryWriter& operator=(const TelemetryWriter&) = delete;

  // Loop side. try_push never blocks; it returns false when the queue is full (counted).
  bool try_push(const TelemetryRecord& r) noexcept;
  // For replays, which must keep every record: waits (yielding) while the queue is full.
  void push_wait(const TelemetryRecord& r) noexcept;
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
  // True once the writer thread failed (disk full, ...); the loop treats it as a fault.
  bool failed() const noexcept { return failed_.load(std::memory_order_acquire); }
  std::string failure() const;
  // Drain the queue, close the file, join the thread. Throws if the writer failed.
  void finish();
  std::uint64_t written() const noexcept { return written_.load(std::memory_order_relaxed); }

 private:
  void run() noexcept;
  // Throws (ending the writer) when `more` bytes would break the budget or the disk is nearly full.
  void check_room(std::uint64_t more);

  std::filesystem::path path_;
  TelemetryFormat format_;
  TelemetryLimits limits_;
  std::uint64_t bytes_ = 0, bytes_at_space_check_ = 0;  // writer thread only
  std::unique_ptr<boost::lockfree::spsc_queue<TelemetryRecord>> queue_;
  std::atomic<bool> done_{false}, failed_{false};
  std::atomic<std::uint64_t> dropped_{0}, written_{0};
  std::string failure_;
  std::thread thread_;
};

void write_telemetry_csv_header(std::ostream& out);
void write_telemetry_csv_row(std::ostream& out, const TelemetryRecord& r);
// Convert a binary telemetry file to CSV; throws InputError on a file that is not one (no CSV is
// left then), OutputError when the CSV cannot be written whole (io/checked_output.hpp).
std::uint64_t convert_telemetry_to_csv(const std::filesystem::path& binary, const std::filesystem::path& csv);

}  // namespace palprig
