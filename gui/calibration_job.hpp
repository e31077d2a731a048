#pragma once
// CalibrationJob: one calibration sweep on its own thread, so the window keeps drawing while
// the rig holds its levels. It calls calibration/sweep_recording (the same plan, runner and
// data file as `palprig calibrate sweep`) on a backend the window has handed over: the live
// loop is stopped and vented first, so the backend has one owner at a time. The GUI reads
// progress from atomics on its poll timer; the worker never emits a Qt signal. stop() sets the
// sweep's stop flag: the runner vents every channel and the data recorded so far is kept.
#include <atomic>
#include <filesystem>
#include <string>
#include <thread>

#include "calibration/sweep_recording.hpp"

namespace palprig::gui {

class CalibrationJob {
 public:
  // Starts at once. The backend must stay alive until finished() (the destructor waits).
  CalibrationJob(RigBackend& backend, RigConfig rig, SweepSchedule schedule, SweepRunOptions options,
                 std::filesystem::path data_path);
  ~CalibrationJob();  // stop() and join
  CalibrationJob(const CalibrationJob&) = delete;
  CalibrationJob& operator=(const CalibrationJob&) = delete;

  void stop() noexcept { stop_flag_.store(1); }
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }
  std::size_t holds_done() const noexcept { return done_.load(std::memory_order_relaxed); }
  std::size_t holds_total() const noexcept { return total_; }
  // Valid once finished(): the outcome, or error() when the data file could not be written.
  const SweepRecording& recording() const noexcept { return recording_; }
  const std::string& error() const noexcept { return error_; }
  const std::filesystem::path& data_path() const noexcept { return data_path_; }

 private:
  std::filesystem::path data_path_;
  std::size_t total_ = 0;
  std::atomic<int> stop_flag_{0};
  std::atomic<std::size_t> done_{0};
  std::atomic<bool> finished_{false};
  SweepRecording recording_;  // written by the worker before finished_, read after
  std::string error_;
  std::thread worker_;
};

}  // namespace palprig::gui
