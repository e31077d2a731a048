#pragma once
// CalibrationJob: one calibration sweep, or one compensation evaluation, on its own thread, so
// the window keeps drawing while the rig holds its levels. A sweep calls
// calibration/sweep_recording (the same plan, runner and data file as `palprig calibrate
// sweep`); an evaluation calls evaluate_compensation (as `palprig calibrate evaluate`) and draws
// its charts (gui/calibration_charts' plot_evaluation) before it finishes. Both drive the rig
// through a lease on the window's rig (controller/rig_lease.hpp: the live loop gave way), which
// the job holds until it is destroyed. The GUI reads progress from atomics on its poll timer; the
// worker never emits a Qt signal. stop() asks the window's RunControl to stop: the runner vents
// every channel and what was recorded so far is kept.
#include <atomic>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "calibration/compensation_evaluation.hpp"
#include "calibration/sweep_recording.hpp"
#include "charts/calibration_charts.hpp"

namespace palprig::gui {

class CalibrationJob {
 public:
  // A sweep; starts at once, on the rig `lease` gives (given back when the job is destroyed).
  // `control` is the window's operator handle (restarted here: a new run).
  CalibrationJob(RigLease lease, RunControl& control, RigConfig rig, SweepSchedule schedule, SweepRunOptions options,
                 std::filesystem::path data_path);
  // An evaluation of `cal` (read from its file as the CLI reads it); its charts go to chart_dir.
  CalibrationJob(RigLease lease, RunControl& control, RigConfig rig, CalibrationModels cal, EvaluationOptions options,
                 std::filesystem::path chart_dir);
  ~CalibrationJob();  // stop() and join
  CalibrationJob(const CalibrationJob&) = delete;
  CalibrationJob& operator=(const CalibrationJob&) = delete;

  void stop() noexcept { control_.request_stop(); }
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }
  bool is_evaluation() const noexcept { return evaluation_channels_.has_value(); }
  std::size_t holds_done() const noexcept { return done_.load(std::memory_order_relaxed); }
  std::size_t holds_total() const noexcept { return total_; }  // 0 for an evaluation (no progress count)
  // Valid once finished(): the outcome, or error() when the data file could not be written or
  // the library refused the evaluation.
  const SweepRecording& recording() const noexcept { return recording_; }
  const std::optional<EvaluationResult>& evaluation() const noexcept { return evaluation_; }
  // The evaluation's charts as data (made on the worker), for the GUI thread to draw into chart_dir().
  const std::vector<charts::NamedChart>& evaluation_charts() const noexcept { return charts_; }
  const std::filesystem::path& chart_dir() const noexcept { return chart_dir_; }
  const std::array<bool, kFingerCount>& evaluated_channels() const noexcept { return *evaluation_channels_; }
  const std::string& error() const noexcept { return error_; }
  const std::filesystem::path& data_path() const noexcept { return data_path_; }

 private:
  RigLease lease_;  // the worker's way to the rig; given back after the worker is joined
  RunControl& control_;
  std::filesystem::path data_path_;
  std::size_t total_ = 0;
  std::atomic<std::size_t> done_{0};
  std::atomic<bool> finished_{false};
  // Written by the worker before finished_, read after.
  SweepRecording recording_;
  std::optional<EvaluationResult> evaluation_;
  std::optional<std::array<bool, kFingerCount>> evaluation_channels_;
  std::vector<charts::NamedChart> charts_;
  std::filesystem::path chart_dir_;
  std::string error_;
  std::thread worker_;
};

}  // namespace palprig::gui
