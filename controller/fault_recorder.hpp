#pragma once
// FaultRecorder: the last ticks before a fault, kept always. RigStep records every step's
// telemetry record into a fixed ring, allocated when the step is made, so the loop's thread never
// allocates and does no I/O for it; when a run ends on a fault its front end writes the ring
// beside the run (write_fault_record) and names the file in its one-line message. "Why did it
// vent" is then answerable whether or not telemetry was on.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "controller/fault.hpp"
#include "controller/telemetry.hpp"

namespace palprig {

// Ticks kept: 2 s at 1 kHz (about 300 KB), enough to see a regulator, a link or a pen go wrong.
inline constexpr std::size_t kFaultRecordTicks = 2000;

class FaultRecorder {
 public:
  explicit FaultRecorder(std::size_t capacity = kFaultRecordTicks) : ring_(capacity > 0 ? capacity : 1) {}

  // Loop thread: keep this record, forgetting the oldest when full. No allocation.
  void record(const TelemetryRecord& r) noexcept {
    ring_[next_ % ring_.size()] = r;
    ++next_;
  }
  std::size_t size() const noexcept { return next_ < ring_.size() ? std::size_t(next_) : ring_.size(); }
  // The kept records, oldest first (after the run: this allocates).
  std::vector<TelemetryRecord> records() const;

 private:
  std::vector<TelemetryRecord> ring_;
  std::uint64_t next_ = 0;
};

// Writes the recorder's ticks as telemetry CSV (the columns of `run --telemetry`, readable with a
// CSV reader that skips '#' comments) under comment lines saying what ran and which fault ended
// it. Throws OutputError when the file cannot be written whole (io/checked_output).
void write_fault_record(const std::filesystem::path& path, const FaultRecorder& recorder, const Fault& fault,
                        const std::string& what_ran);

// Where a run's fault record goes: beside its telemetry file (NAME.fault.csv) when it has one,
// else in `folder` as palprig-fault-YYYYMMDDTHHMMSSZ.csv (a number added if that exists).
std::filesystem::path fault_record_path(const std::filesystem::path& telemetry_file,
                                        const std::filesystem::path& folder);

// After a run that faulted: writes the record at fault_record_path and returns the sentence the
// front end appends to its fault line ("the last 2000 ticks before it: FILE"), or why it could
// not be written. Never throws: the run's result is reported either way.
std::string save_fault_record(const FaultRecorder& recorder, const Fault& fault, const std::string& what_ran,
                              const std::filesystem::path& telemetry_file, const std::filesystem::path& folder,
                              std::filesystem::path* written = nullptr);

}  // namespace palprig
