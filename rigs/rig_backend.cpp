#include "rigs/rig_backend.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "core/error.hpp"

namespace palprig {

const char* to_string(BackendState state) noexcept {
  switch (state) {
    case BackendState::closed: return "closed";
    case BackendState::connected: return "connected";
    case BackendState::armed: return "armed";
    case BackendState::disarmed: return "disarmed";
  }
  return "unknown";
}

RigBackend::RigBackend(double p_max_kPa) : p_max_kPa_(p_max_kPa) {
  if (!(p_max_kPa > 0) || !std::isfinite(p_max_kPa))
    throw BadInput("RigBackend: p_max_kPa must be positive and finite");
}

void RigBackend::open() {
  close();
  try {
    do_open();
  } catch (...) {
    do_close();  // whatever was half-opened is let go, vented where it could be written
    state_.store(BackendState::closed, std::memory_order_release);
    throw;
  }
  state_.store(BackendState::connected, std::memory_order_release);
}

void RigBackend::close() noexcept {
  if (state() == BackendState::closed) return;
  // Disarm first, so nothing sees "armed" while the channels are being let go.
  state_.store(BackendState::disarmed, std::memory_order_release);
  do_vent();
  do_close();
  state_.store(BackendState::closed, std::memory_order_release);
}

BackendStatus RigBackend::arm() noexcept {
  const BackendState s = state();
  if (s == BackendState::closed) {
    return set_error("cannot arm: the rig backend is closed (open it first)");
  }
  state_.store(BackendState::armed, std::memory_order_release);
  return BackendStatus::ok;
}

BackendStatus RigBackend::disarm() noexcept {
  if (state() != BackendState::armed) return BackendStatus::ok;
  state_.store(BackendState::disarmed, std::memory_order_release);
  return with_reason(do_vent());
}

BackendStatus RigBackend::write(const ChannelPressures& setpoint_kPa, double t_s) noexcept {
  if (state() != BackendState::armed) {
    char msg[160];
    std::snprintf(msg, sizeof msg, "refused setpoints: the rig is %s, not armed; vented", to_string(state()));
    do_vent();
    return set_error(msg);
  }
  for (std::size_t i = 0; i < setpoint_kPa.size(); ++i) {
    const double p = setpoint_kPa[i];
    if (!std::isfinite(p) || p < 0 || p > p_max_kPa_) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "refused setpoint %.3f kPa on channel %zu (allowed 0..%.1f kPa); vented", p, i + 1,
                    p_max_kPa_);
      do_vent();
      return set_error(msg);
    }
  }
  return with_reason(do_write(setpoint_kPa, t_s));
}

BackendStatus RigBackend::read_monitors(ChannelPressures& monitor_kPa, double t_s) noexcept {
  if (state() == BackendState::closed) {
    return set_error("cannot read monitors: the rig backend is closed (open it first)");
  }
  return with_reason(do_read(monitor_kPa, t_s));
}

BackendStatus RigBackend::read_sensors(std::array<double, kFingerCount>& value, double t_s) noexcept {
  if (state() == BackendState::closed) {
    return set_error("cannot read sensors: the rig backend is closed (open it first)");
  }
  return with_reason(do_read_sensors(value, t_s));
}

BackendStatus RigBackend::do_read_sensors(std::array<double, kFingerCount>& value, double) noexcept {
  value.fill(std::nan(""));
  return set_error("this rig has no sensor channel");
}

BackendStatus RigBackend::vent() noexcept { return with_reason(do_vent()); }

void RigBackend::attach_load_cells(const LoadCellConfig& config) {
  if (state() != BackendState::closed) throw std::logic_error("load cells are attached before open()");
  load_cells_ = config;
}

void RigBackend::describe_load_cells(BackendCapabilities& c) const noexcept {
  c.load_cells = load_cell_count();
  c.load_cells_per_finger = load_cells_per_finger();
}

BackendStatus RigBackend::read_load_cells(LoadCellReading& reading, double t_s) noexcept {
  reading = {};
  reading.volts.fill(std::nan(""));
  reading.force_N.fill(std::nan(""));
  if (!load_cells_) {
    return set_error("this rig has no load cells (the rig file's \"load_cells\" section)");
  }
  if (state() == BackendState::closed) {
    return set_error("cannot read the load cells: the rig backend is closed (open it first)");
  }
  const BackendStatus status = do_read_load_cells(reading.volts, t_s);
  reading.count = load_cells_->channels.size();
  for (std::size_t i = 0; i < reading.count; ++i)
    reading.force_N[i] = load_cells_->channels[i].calibration.force_N(reading.volts[i]);
  return with_reason(status);
}

BackendStatus RigBackend::do_read_load_cells(std::array<double, kFingerCount>& volts, double) noexcept {
  volts.fill(std::nan(""));
  return set_error("this backend cannot read load cells");
}

BackendStatus RigBackend::set_error(const char* message) noexcept {
  std::strncpy(last_error_, message, sizeof last_error_ - 1);
  last_error_[sizeof last_error_ - 1] = '\0';
  return BackendStatus::failure(last_error_);
}

BackendStatus RigBackend::with_reason(BackendStatus status) const noexcept {
  // A backend hook that failed without words of its own has left them in last_error_.
  if (status == BackendStatus::error && status.reason()[0] == '\0') return BackendStatus::failure(last_error_);
  return status;
}

}  // namespace palprig
