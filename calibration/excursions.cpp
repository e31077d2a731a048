#include "calibration/excursions.hpp"

#include <cmath>
#include <cstdio>

namespace palprig {

void ExcursionWatch::add(std::size_t channel, double t_s, double command_kPa, double monitor_kPa) {
  if (channel >= kFingerCount) return;
  Open& o = open_[channel];
  const double off = monitor_kPa - command_kPa;
  if (!std::isfinite(off) || std::fabs(off) <= tolerance_kPa_) {
    if (o.open) {
      o.e.duration_s = o.last_s - o.e.start_s;
      done_.push_back(o.e);
      o.open = false;
    }
    return;
  }
  if (!o.open) {
    o.open = true;
    o.e = Excursion{static_cast<int>(channel) + 1, t_s, 0, off, t_s};
  } else if (std::fabs(off) > std::fabs(o.e.worst_kPa)) {
    o.e.worst_kPa = off;
    o.e.worst_at_s = t_s;
  }
  o.last_s = t_s;
}

void ExcursionWatch::close() {
  for (Open& o : open_) {
    if (!o.open) continue;
    o.e.duration_s = o.last_s - o.e.start_s;
    done_.push_back(o.e);
    o.open = false;
  }
}

std::string excursion_text(const Excursion& e, double tolerance_kPa) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "channel %d: %.1f kPa %s the command at %.2f s (%.2f s beyond %.0f kPa)", e.channel,
                std::fabs(e.worst_kPa), e.worst_kPa < 0 ? "below" : "above", e.worst_at_s, e.duration_s, tolerance_kPa);
  return buf;
}

}  // namespace palprig
