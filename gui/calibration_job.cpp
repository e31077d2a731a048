#include "gui/calibration_job.hpp"

#include "charts/calibration_charts.hpp"

namespace palprig::gui {

CalibrationJob::CalibrationJob(RigBackend& backend, RigConfig rig, SweepSchedule schedule, SweepRunOptions options,
                               std::filesystem::path data_path)
    : data_path_(std::move(data_path)), total_(schedule.holds.size()) {
  options.stop_signal = &stop_flag_;
  worker_ = std::thread([this, &backend, rig = std::move(rig), schedule = std::move(schedule), options] {
    try {
      recording_ = record_calibration_sweep(
          backend, rig, schedule, options, data_path_,
          [this](std::size_t done, std::size_t, const SweepHold&, const HoldOutcome&) { done_.store(done); });
    } catch (const std::exception& e) {
      error_ = e.what();
      backend.vent();  // the runner vents on its own errors; this covers the data file's
    }
    finished_.store(true, std::memory_order_release);
  });
}

CalibrationJob::CalibrationJob(RigBackend& backend, RigConfig rig, CalibrationModels cal, EvaluationOptions options,
                               std::filesystem::path chart_dir)
    : evaluation_channels_(options.channels), chart_dir_(std::move(chart_dir)) {
  options.stop_signal = &stop_flag_;
  worker_ = std::thread([this, &backend, rig = std::move(rig), cal = std::move(cal), options] {
    try {
      evaluation_ = evaluate_compensation(backend, rig, cal, options);
      // As data only: QCustomPlot draws on the GUI thread (CalibrationPage::evaluation_done).
      charts_ = charts::evaluation_charts(*evaluation_, options.channels);
    } catch (const std::exception& e) {
      error_ = e.what();
      backend.vent();
    }
    finished_.store(true, std::memory_order_release);
  });
}

CalibrationJob::~CalibrationJob() {
  stop();
  if (worker_.joinable()) worker_.join();
}

}  // namespace palprig::gui
