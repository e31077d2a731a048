#include "calibration/progress_meter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace palprig {

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "unknown";
  const long s = std::lround(seconds);
  char buf[48];
  if (seconds < 9.95)
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  else if (s < 60)
    std::snprintf(buf, sizeof buf, "%ld s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  return buf;
}

std::string progress_line(const ProgressReport& r) {
  char done[16];
  std::snprintf(done, sizeof done, "%.0f %%", 100.0 * std::clamp(r.done, 0.0, 1.0));
  if (r.done >= 1.0) return r.step + ": done in " + duration_text(r.elapsed_s);
  std::string line = r.step + ": " + r.phase + ", " + done + " done, " + duration_text(r.elapsed_s) + " so far";
  return line +
         (std::isfinite(r.left_s) ? ", about " + duration_text(r.left_s) + " left" : ", time left not known yet");
}

ProgressMeter::ProgressMeter(std::string step, ProgressSink sink, double every_s, double quiet_s)
    : sink_(std::move(sink)),
      every_s_(every_s),
      quiet_s_(quiet_s),
      started_(std::chrono::steady_clock::now()),
      last_report_(started_) {
  current_.step = std::move(step);
}

void ProgressMeter::phase(const std::string& name, double done) {
  if (name == current_.phase) return update(done);
  current_.phase = name;
  report(done);
}

void ProgressMeter::update(double done) {
  if (!sink_ || (++calls_ & 63u) != 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_report_).count() >= every_s_) report(done);
}

void ProgressMeter::finish() {
  if (reported_) report(1.0);
}

void ProgressMeter::report(double done) {
  if (!sink_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed_s = std::chrono::duration<double>(now - started_).count();
  if (elapsed_s < quiet_s_) return;
  current_.done = std::clamp(done, 0.0, 1.0);
  current_.elapsed_s = elapsed_s;
  current_.left_s = current_.done > 0.005 ? current_.elapsed_s * (1.0 - current_.done) / current_.done
                                          : std::numeric_limits<double>::quiet_NaN();
  last_report_ = now;
  reported_ = true;
  sink_(current_);
}

}  // namespace palprig
