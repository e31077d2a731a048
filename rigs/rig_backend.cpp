#include "rigs/rig_backend.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace palprig {

RigBackend::RigBackend(double p_max_kPa) : p_max_kPa_(p_max_kPa) {
  if (!(p_max_kPa > 0) || !std::isfinite(p_max_kPa))
    throw std::invalid_argument("RigBackend: p_max_kPa must be positive and finite");
}

BackendStatus RigBackend::write(const ChannelPressures& setpoint_kPa, double t_s) noexcept {
  for (std::size_t i = 0; i < setpoint_kPa.size(); ++i) {
    const double p = setpoint_kPa[i];
    if (!std::isfinite(p) || p < 0 || p > p_max_kPa_) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "refused setpoint %.3f kPa on channel %zu (allowed 0..%.1f kPa); vented",
                    p, i + 1, p_max_kPa_);
      do_vent();
      set_error(msg);
      return BackendStatus::error;
    }
  }
  return do_write(setpoint_kPa, t_s);
}

BackendStatus RigBackend::read_monitors(ChannelPressures& monitor_kPa, double t_s) noexcept {
  return do_read(monitor_kPa, t_s);
}

BackendStatus RigBackend::vent() noexcept { return do_vent(); }

void RigBackend::set_error(const char* message) noexcept {
  std::strncpy(last_error_, message, sizeof last_error_ - 1);
  last_error_[sizeof last_error_ - 1] = '\0';
}

}  // namespace palprig
