#pragma once
// Where pen samples come from. The loop asks for the latest sample at its own time; a source
// never blocks, allocates or throws in latest(). Recorded traces and scripted pen rasters are here;
// the pen tablet (evdev) and the GUI pointer implement the same interface.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "models/touch_sample.hpp"
#include "models/scene.hpp"

namespace palprig {

class InputSource {
 public:
  virtual ~InputSource() = default;
  virtual TouchSample latest(double t_s) noexcept = 0;
  // Length of a finite source (a trace, a raster); 0 for a live one.
  virtual double duration_s() const noexcept = 0;
  virtual std::string describe() const = 0;
};

// A recorded trace: CSV with header t_s,x_mm,y_mm,force_N and strictly increasing times.
// Between rows the pen is interpolated linearly; after the last row it stays lifted.
class TraceInput final : public InputSource {
 public:
  TraceInput(std::vector<TouchSample> samples, std::string name, double contact_force_N = 0.05);
  TouchSample latest(double t_s) noexcept override;
  double duration_s() const noexcept override { return samples_.empty() ? 0 : samples_.back().t_s; }
  std::string describe() const override { return "trace " + name_; }
  const std::vector<TouchSample>& samples() const noexcept { return samples_; }

 private:
  std::vector<TouchSample> samples_;
  std::string name_;
  std::size_t cursor_ = 0;  // the loop's time only moves forward: search from here
};

// What a trace may hold before it is refused. A trace's times are relative to its first row
// (a recorder's epoch timestamps are fine), but a trace that runs for days, or whose rows are
// further apart than the loop's stale-input limit, is almost always a mistake (a unit error,
// a clock jump) and would replay for ever into the telemetry. unbounded() lifts both, for a
// run whose length is given explicitly.
struct TraceLimits {
  double max_length_s = 3600.0;  // one hour
  double max_gap_s = 0.1;        // the rig's safety.max_input_age_s
  static TraceLimits unbounded();
};

// Refused because of TraceLimits (not malformed): the command line says how to run it anyway.
class TraceBoundError : public InputError {
 public:
  using InputError::InputError;
};

// Reads the trace and shifts its times so the first row is at t = 0 s.
std::vector<TouchSample> load_trace_csv(const std::filesystem::path& path, double contact_force_N = 0.05,
                                        const TraceLimits& limits = {});
void write_trace_csv(const std::filesystem::path& path, const std::vector<TouchSample>& samples);

// A scripted pen raster over a scene's bounds at constant speed and force: rows spaced
// row_step_mm apart, travelling back and forth, pen pressed the whole time. (`--input sweep`
// on the command line; "sweep" in code is calibration's staircase.)
struct RasterPlan {
  double speed_mm_per_s = 40.0;
  double row_step_mm = 10.0;
  double force_N = 2.0;
  double margin_mm = 5.0;
};

class RasterInput final : public InputSource {
 public:
  RasterInput(const SceneBounds& bounds, const RasterPlan& plan);
  TouchSample latest(double t_s) noexcept override;
  double duration_s() const noexcept override { return duration_s_; }
  std::string describe() const override { return "raster"; }

 private:
  SceneBounds area_;
  RasterPlan plan_;
  double row_length_mm_ = 0, duration_s_ = 0;
  int rows_ = 0;
};

}  // namespace palprig
