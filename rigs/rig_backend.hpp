#pragma once
// RigBackend: the seam between the loop and the pressure regulators. The simulated, Modbus and
// comedi rigs implement do_write/do_read/do_vent; the public write() enforces the rig's p_max a
// second time (after the tick's safety stage) so that no value above p_max, NaN or infinite ever
// reaches a device, whatever called it. Everything the loop calls is noexcept and returns a
// status; only open() may throw (before anything moves).
#include <array>
#include <cstddef>
#include <string>

#include "models/channel_pressures.hpp"

namespace palprig {

enum class BackendStatus { ok, error };

class RigBackend {
 public:
  explicit RigBackend(double p_max_kPa);
  virtual ~RigBackend() = default;
  RigBackend(const RigBackend&) = delete;
  RigBackend& operator=(const RigBackend&) = delete;

  // Connect and vent. Throws std::runtime_error with one clear line on failure.
  virtual void open() = 0;
  virtual void close() noexcept = 0;
  virtual std::string describe() const = 0;  // e.g. "simulated", "modbus tcp 127.0.0.1:1502"

  // Setpoints for all channels at loop time t_s. A non-finite value or one above p_max is not
  // sent: the backend vents instead and returns error with the reason in last_error().
  BackendStatus write(const ChannelPressures& setpoint_kPa, double t_s) noexcept;
  // Latest monitor pressures reported by the regulators.
  BackendStatus read_monitors(ChannelPressures& monitor_kPa, double t_s) noexcept;
  // All channels to 0 kPa. Safe to call repeatedly and after errors.
  BackendStatus vent() noexcept;

  // Whether commands currently reach the regulators. A backend whose link can drop and come back
  // (Modbus) returns false while it is vented and reconnecting; the loop then raises an alarm in
  // telemetry instead of stopping. In-process and directly attached backends are always linked.
  virtual bool linked() const noexcept { return true; }

  double p_max_kPa() const noexcept { return p_max_kPa_; }
  const char* last_error() const noexcept { return last_error_; }

  // Optional sensor per channel (actuator deformation or fingertip force) that calibration
  // sweeps record beside the monitors. A backend with one returns its name with the unit
  // (e.g. "deformation_mm") and overrides read_sensors; the defaults mean "no sensor".
  virtual const char* sensor_name() const noexcept { return nullptr; }
  virtual BackendStatus read_sensors(std::array<double, kFingerCount>& value, double t_s) noexcept {
    (void)value;
    (void)t_s;
    set_error("this rig has no sensor channel");
    return BackendStatus::error;
  }

 protected:
  virtual BackendStatus do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept = 0;
  virtual BackendStatus do_read(ChannelPressures& monitor_kPa, double t_s) noexcept = 0;
  virtual BackendStatus do_vent() noexcept = 0;
  // Record why the last call failed (copied into a fixed buffer: no allocation).
  void set_error(const char* message) noexcept;

 private:
  double p_max_kPa_;
  char last_error_[256] = {0};
};

}  // namespace palprig
