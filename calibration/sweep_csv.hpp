#pragma once
// The sweep data file (DATA.csv): a few "# key: value" lines that say where it came from,
// then one row per sample and channel:
//
//   # palprig calibration sweep
//   # rig_id: sim-default
//   # backend: simulated
//   # date: 2026-11-22T12:00:00Z
//   # p_max_kPa: 60
//   # rate_hz: 100
//   # sensor: none                (or the sensor's name with its unit, e.g. deformation_mm)
//   t_s,channel,hold,segment,repeat,branch,command_kPa,monitor_kPa,sensor,settled
//   0.010,1,0,vent,0,none,0,0.03,,0
//
// `calibrate fit` averages the settled rows of each hold into one quasi-static point; the rows
// of step and chirp holds (segment step or chirp: a command that changes within the hold, at
// the dynamics rate) are kept sample by sample for the dynamics fit. The
// same reader takes a table typed in by hand (e.g. caliper readings, as in paper 002): only
// channel, command_kPa and one of monitor_kPa / sensor are required; without a hold column
// every row is its own point, without a settled column every row counts as settled.
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "calibration/sweep_runner.hpp"

namespace palprig {

struct SweepFileInfo {
  std::string rig_id, backend, date;
  std::string sensor_name;  // empty: no sensor
  double p_max_kPa = std::numeric_limits<double>::quiet_NaN();
  double rate_hz = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> notes;
};

class SweepCsvWriter final : public SweepSink {
 public:
  // Throws OutputError (io/checked_output.hpp: the file and the system's reason) when the file
  // cannot be created; on_hold and finish likewise when a flush or the close fails.
  SweepCsvWriter(const std::filesystem::path& path, const SweepFileInfo& info,
                 const std::array<bool, kFingerCount>& channels);
  void on_hold(std::size_t index, const SweepHold& hold, std::span<const SweepSample> samples,
               const HoldOutcome& outcome) override;
  // Trailing comment lines: how the sweep ended.
  void finish(const SweepOutcome& outcome);
  std::size_t rows() const noexcept { return rows_; }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::array<bool, kFingerCount> channels_;
  bool has_sensor_;
  std::size_t rows_ = 0;
};

// One hold of one channel: the mean of its settled rows.
struct HoldPoint {
  int channel = 0;  // 1-based
  long hold = 0;
  SweepSegment segment = SweepSegment::staircase;
  int repeat = 0;
  SweepBranch branch = SweepBranch::none;
  double command_kPa = 0;
  double monitor_kPa = std::numeric_limits<double>::quiet_NaN();  // NaN: no reading
  double sensor = std::numeric_limits<double>::quiet_NaN();
  std::size_t samples = 0;
  std::size_t line = 0;  // first line of the hold in the file, for messages
};

// One sample of a step or chirp hold (the dynamics fit's data), in file order.
struct DynamicsSample {
  int channel = 0;  // 1-based
  long hold = 0;
  SweepSegment segment = SweepSegment::step;
  double t_s = 0;
  double command_kPa = 0;  // the setpoint sent
  double monitor_kPa = std::numeric_limits<double>::quiet_NaN();
  std::size_t line = 0;
};

struct SweepData {
  std::string file;
  SweepFileInfo info;
  bool has_monitor = false, has_sensor = false;
  std::vector<HoldPoint> points;  // in file (time) order, every channel
  std::vector<int> channels;      // channels present, ascending
  std::size_t rows = 0;
  std::size_t unsettled_holds = 0;  // holds with no settled row (left out of the points)

  std::vector<DynamicsSample> dynamics;  // step and chirp rows, every channel, in file order

  std::vector<HoldPoint> channel_points(int channel) const;
  std::vector<DynamicsSample> channel_dynamics(int channel) const;
};

// Throws InputError naming the file and line for anything malformed.
SweepData read_sweep_csv(const std::filesystem::path& path);

}  // namespace palprig
