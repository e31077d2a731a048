#pragma once
// What a long calibration step says while it runs: the share done, the wall time it has taken
// and the time left, at each change of phase ("staircase repeat 2/5", "compensated run") and at
// least every few seconds in between. Over a real link a sweep takes minutes and an evaluation
// two runs of two minutes each; a command that prints nothing meanwhile looks hung.
//
// The share done is the caller's (rig time, holds, channels fitted); the time left is the wall
// time so far scaled by what is left of the share, so it holds over a slow link as on simulated
// time. update() is cheap enough for every tick of a calibration loop (it reads the clock once
// every 64 calls); it is not for the real-time tick.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace palprig {

struct ProgressReport {
  std::string step;   // "sweep", "fit", "evaluate"
  std::string phase;  // what runs now
  double done = 0;    // share of the step done, 0..1
  double elapsed_s = 0;
  double left_s = 0;  // NaN until something is done to estimate from
};

using ProgressSink = std::function<void(const ProgressReport&)>;

// "2 min 05 s", "48 s", "1 h 02 min": a duration for a person.
std::string duration_text(double seconds);
// "sweep: staircase repeat 2/5, 23 % done, 1 min 40 s so far, about 5 min 30 s left"
std::string progress_line(const ProgressReport& report);

class ProgressMeter {
 public:
  // Reports go to `sink` (none: the meter is silent) at most every `every_s` of wall time
  // between phase changes; none before `quiet_s` (a step that is over in a second, such as a
  // fit, says nothing).
  ProgressMeter(std::string step, ProgressSink sink, double every_s = 5.0, double quiet_s = 0.0);

  // A new phase is reported at once (with the share done so far).
  void phase(const std::string& name, double done);
  // The share done now; reported when every_s has passed since the last report.
  void update(double done);
  // The step's end (100 %), reported unless nothing was ever reported.
  void finish();

 private:
  void report(double done);

  ProgressReport current_;
  ProgressSink sink_;
  double every_s_, quiet_s_;
  std::chrono::steady_clock::time_point started_, last_report_;
  std::uint32_t calls_ = 0;
  bool reported_ = false;
};

}  // namespace palprig
