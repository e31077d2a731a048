#include "gui/calibration_job.hpp"

#include "charts/calibration_charts.hpp"

namespace palprig::gui {

namespace {
// The window's simulated rig, which its live loop drove until now: opened again, so a sweep or
// an evaluation starts from regulators at rest with their noise seeded afresh, as on the rig
// `palprig calibrate` opens for itself (sessions do the same: sessions/study_rig.cpp). Without
// it the figures depended on how long the live loop had run. Hardware is not touched.
void start_fresh_if_simulated(RigLease& lease, const RigConfig& rig) {
  if (rig.backend == "simulated") lease.backend().open();
}
}  // namespace

CalibrationJob::CalibrationJob(RigLease lease, RunControl& control, RigConfig rig, SweepSchedule schedule,
                               SweepRunOptions options, std::filesystem::path data_path)
    : lease_(std::move(lease)), control_(control), data_path_(std::move(data_path)), total_(schedule.holds.size()) {
  control_.restart();
  options.control = &control_;
  worker_ = std::thread([this, rig = std::move(rig), schedule = std::move(schedule), options] {
    try {
      start_fresh_if_simulated(lease_, rig);
      recording_ = record_calibration_sweep(
          lease_, rig, schedule, options, data_path_,
          [this](std::size_t done, std::size_t, const SweepHold&, const HoldOutcome&) { done_.store(done); });
    } catch (const std::exception& e) {
      error_ = e.what();
      lease_.backend().vent();  // the runner vents on its own errors; this covers the data file's
    }
    finished_.store(true, std::memory_order_release);
  });
}

CalibrationJob::CalibrationJob(RigLease lease, RunControl& control, RigConfig rig, CalibrationModels cal,
                               EvaluationOptions options, std::filesystem::path chart_dir)
    : lease_(std::move(lease)),
      control_(control),
      evaluation_channels_(options.channels),
      chart_dir_(std::move(chart_dir)) {
  control_.restart();
  options.control = &control_;
  worker_ = std::thread([this, rig = std::move(rig), cal = std::move(cal), options] {
    try {
      start_fresh_if_simulated(lease_, rig);
      evaluation_ = evaluate_compensation(lease_, rig, cal, options);
      // As data only: QCustomPlot draws on the GUI thread (CalibrationPage::evaluation_done).
      charts_ = charts::evaluation_charts(*evaluation_, options.channels);
    } catch (const std::exception& e) {
      error_ = e.what();
      lease_.backend().vent();
    }
    finished_.store(true, std::memory_order_release);
  });
}

CalibrationJob::~CalibrationJob() {
  stop();
  if (worker_.joinable()) worker_.join();
}

}  // namespace palprig::gui
