#pragma once
// RigBackend: the seam between the loop and the pressure regulators. The simulated, Modbus and
// comedi rigs implement do_open/do_close/do_write/do_read/do_vent; the public calls here are
// non-virtual and hold the rules every backend shares:
//
//   - a lifecycle, as ros2_control's hardware interfaces have one, so that an operator (the GUI)
//     sees a device connected and reading before pressure can flow:
//
//        closed --open()--> connected --arm()--> armed --disarm()--> disarmed --arm()--> armed
//           ^                   |                  |                     |
//           +------close()------+------------------+---------------------+
//
//     connected and disarmed: every channel vented, monitors (and sensors) readable.
//     armed: setpoints flow (RigStep ramps them up from the vented state through the slew
//     limit). write() in any other state is refused and vents.
//   - p_max enforced a second time (after the tick's safety stage): no value above p_max, NaN
//     or infinite ever reaches a device, whatever called write().
//   - capabilities described up front (channels, monitor, sensor and its unit, link kind,
//     endpoint) instead of discovered by calling and failing.
//
// Everything the loop calls is noexcept and returns a status; only open() may throw (before
// anything moves). state() may be read from any thread; the transitions are made by the thread
// that owns the backend (the loop while one runs).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "formats/load_cell_config.hpp"
#include "models/channel_pressures.hpp"

namespace palprig {

// What a backend call did: ok, or failed with the backend's own words. The words live in the
// backend's fixed buffer (no allocation on the loop's path) until its next failure, so a caller
// that keeps them longer copies them (RigStep's Fault does). `status == BackendStatus::ok` and
// `== BackendStatus::error` compare the outcome.
class BackendStatus {
 public:
  struct Ok {};
  struct Failed {};
  static constexpr Ok ok{};
  static constexpr Failed error{};
  constexpr BackendStatus(Ok = {}) noexcept {}  // NOLINT(google-explicit-constructor): `return BackendStatus::ok;`
  constexpr BackendStatus(Failed) noexcept : failed_(true) {}  // NOLINT(google-explicit-constructor)
  static constexpr BackendStatus failure(const char* reason) noexcept {
    BackendStatus s{Failed{}};
    s.reason_ = reason;
    return s;
  }
  constexpr bool succeeded() const noexcept { return !failed_; }
  // Why it failed, in the backend's words; "" when it succeeded (or a backend gave none).
  constexpr const char* reason() const noexcept { return reason_ ? reason_ : ""; }
  friend constexpr bool operator==(const BackendStatus& s, Ok) noexcept { return !s.failed_; }
  friend constexpr bool operator==(const BackendStatus& s, Failed) noexcept { return s.failed_; }

 private:
  bool failed_ = false;
  const char* reason_ = nullptr;
};

enum class BackendState { closed, connected, armed, disarmed };
const char* to_string(BackendState state) noexcept;

// What a backend offers, known before anything is written (the GUI's rig panel shows it).
struct BackendCapabilities {
  std::size_t channel_count = kFingerCount;
  bool has_monitor = true;             // regulators report their output pressure
  bool has_sensor = false;             // a per-channel sensor calibration sweeps record beside the monitors
  std::string sensor_name;             // with its unit, e.g. "deformation_mm"; empty without a sensor
  std::string sensor_unit;             // e.g. "mm"
  std::string link_kind;               // "in-process", "modbus-tcp", "modbus-rtu", "comedi"
  std::string endpoint;                // e.g. "127.0.0.1:1502", "/dev/ttyUSB0 9600 8N1", "/dev/comedi0"
  std::size_t load_cells = 0;          // load cells measuring the pressing force: 0, 1 or 3
  bool load_cells_per_finger = false;  // 3 cells, one under each finger; else 1 shared
};

// One reading of the load cells: each cell's voltage and its force (its calibration applied).
struct LoadCellReading {
  std::size_t count = 0;  // cells read: 1 (shared) or kFingerCount
  std::array<double, kFingerCount> volts{};
  std::array<double, kFingerCount> force_N{};
};

class RigBackend {
 public:
  explicit RigBackend(double p_max_kPa);
  virtual ~RigBackend() = default;
  RigBackend(const RigBackend&) = delete;
  RigBackend& operator=(const RigBackend&) = delete;

  // closed (or any state: closes first) -> connected: connect, vent, ready to read. Throws
  // Error (InputError for configuration) with one clear line on failure; the
  // backend is then closed.
  void open();
  // any -> closed: vent and disconnect. Safe to call repeatedly.
  void close() noexcept;
  // connected or disarmed -> armed. Refused (error, last_error says why) when closed.
  BackendStatus arm() noexcept;
  // armed -> disarmed: every channel vented, monitors still read. No change in other states.
  BackendStatus disarm() noexcept;
  BackendState state() const noexcept { return state_.load(std::memory_order_acquire); }
  bool armed() const noexcept { return state() == BackendState::armed; }

  virtual std::string describe() const = 0;  // e.g. "simulated", "modbus tcp 127.0.0.1:1502"
  virtual BackendCapabilities capabilities() const = 0;

  // Setpoints for all channels at loop time t_s. Refused (vent, error with the reason in
  // last_error()) when not armed, or for a value that is non-finite or outside 0..p_max.
  BackendStatus write(const ChannelPressures& setpoint_kPa, double t_s) noexcept;
  // Latest monitor pressures reported by the regulators (any state but closed).
  BackendStatus read_monitors(ChannelPressures& monitor_kPa, double t_s) noexcept;
  // The sensor channels (capabilities().has_sensor); error on a backend without one.
  BackendStatus read_sensors(std::array<double, kFingerCount>& value, double t_s) noexcept;
  // All channels to 0 kPa, in any state. Safe to call repeatedly and after errors.
  BackendStatus vent() noexcept;

  // The rig file's load cells, given before open(); the backend reads them on its
  // analog inputs. read_load_cells: any state but closed; error without load cells. The
  // force is the cell's calibration applied to its voltage (negative below the tare: noise).
  void attach_load_cells(const LoadCellConfig& config);
  std::size_t load_cell_count() const noexcept { return load_cells_ ? load_cells_->channels.size() : 0; }
  bool load_cells_per_finger() const noexcept { return load_cells_ && load_cells_->per_finger; }
  BackendStatus read_load_cells(LoadCellReading& reading, double t_s) noexcept;
  // How deep each fingertip presses into the phantom (mm below its surface; 0 above it), as the
  // input tracks it: the simulated rig's load cells feel that press. Real cells feel the real
  // finger, so a hardware backend ignores it.
  virtual void feel_press(const std::array<double, kFingerCount>& depth_mm) noexcept { (void)depth_mm; }

  // Whether commands currently reach the regulators. A backend whose link can drop and come back
  // (Modbus) returns false while it is vented and reconnecting; the loop then raises an alarm in
  // telemetry instead of stopping. In-process and directly attached backends are always linked.
  virtual bool linked() const noexcept { return true; }
  // How many times since open() the backend took the pressure off on its own: a link lost, or
  // (Modbus) no setpoint from the loop within the bus's setpoint timeout while pressure was
  // asked for. A step that sees this count change knows the plant was vented since the last
  // one, even when the vent was over before linked() could show it: after a stall of the
  // machine longer than the timeout, the I/O thread may vent and the next setpoint ramp the
  // plant up again from 0 between two steps. Backends without their own I/O thread never do.
  virtual std::uint64_t forced_vents() const noexcept { return 0; }

  double p_max_kPa() const noexcept { return p_max_kPa_; }
  const char* last_error() const noexcept { return last_error_; }
  // Shorthand for capabilities().sensor_name; empty without a sensor.
  std::string sensor_name() const { return capabilities().sensor_name; }

 protected:
  virtual void do_open() = 0;
  virtual void do_close() noexcept = 0;
  virtual BackendStatus do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept = 0;
  virtual BackendStatus do_read(ChannelPressures& monitor_kPa, double t_s) noexcept = 0;
  virtual BackendStatus do_vent() noexcept = 0;
  // Backends with a sensor override this (and say so in capabilities()).
  virtual BackendStatus do_read_sensors(std::array<double, kFingerCount>& value, double t_s) noexcept;
  // Backends that read load cells override this: the first load_cell_count() voltages.
  virtual BackendStatus do_read_load_cells(std::array<double, kFingerCount>& volts, double t_s) noexcept;
  const std::optional<LoadCellConfig>& load_cells() const noexcept { return load_cells_; }
  // capabilities() of a backend with load cells: fills the load-cell fields.
  void describe_load_cells(BackendCapabilities& c) const noexcept;
  // Record why the last call failed (copied into a fixed buffer: no allocation) and return the
  // failure carrying those words: `return set_error("...");`.
  BackendStatus set_error(const char* message) noexcept;

 private:
  // A failed hook's status with the backend's words attached when it gave none.
  BackendStatus with_reason(BackendStatus status) const noexcept;

 protected:
 private:
  double p_max_kPa_;
  std::optional<LoadCellConfig> load_cells_;
  std::atomic<BackendState> state_{BackendState::closed};
  char last_error_[256] = {0};
};

}  // namespace palprig
