#pragma once
// ModbusRig: the regulators on Modbus analog-output/input modules (TCP or RTU) through libmodbus.
//
// The bus never stalls the loop. A bus cycle (write three setpoints, read three monitors) can
// take milliseconds (RTU at 9600 baud, a slow module), so it runs on its own I/O thread at its
// own rate (modbus.io_rate_hz); write() only hands the thread the newest setpoints and read
// returns the newest monitors, both through wait-free LatestValue exchanges.
//
// Lost peer (timeout, reset, refused): the rig enters its vent state at once: every link still
// up is written 0 kPa, linked() turns false (the loop raises an alarm in telemetry and lifts the
// pen), monitors read NaN, and the thread reconnects with exponential backoff. When every link
// is back, outputs are written 0 first and then follow the loop's setpoints through a ramp at
// the rig's slew limit, so a returning peer never sees a pressure step. The same ramp applies
// after the loop went silent (setpoint_timeout) and after open().
//
// A device that answers with a Modbus exception (it refuses the map), a link down longer than
// max_outage_s, or an exception on the I/O thread are faults: write() returns error and the
// loop vents and stops.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "runtime/latency_histogram.hpp"
#include "runtime/latest_value.hpp"
#include "rigs/modbus_link.hpp"
#include "formats/modbus_register_map.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig {

struct ModbusBusStats {
  std::uint64_t cycles = 0, late_cycles = 0, outages = 0, reconnects = 0;
  LatencySummary cycle_time;  // one bus cycle (all links), microseconds
};

class ModbusRig final : public RigBackend {
 public:
  using LogSink = std::function<void(const std::string&)>;

  explicit ModbusRig(ModbusRigConfig config);
  ~ModbusRig() override;

  std::string describe() const override;
  // link_kind "modbus-tcp" or "modbus-rtu" ("modbus-tcp+rtu" when links mix), endpoints joined by " + ".
  BackendCapabilities capabilities() const override;
  bool linked() const noexcept override { return linked_.load(std::memory_order_acquire); }
  std::uint64_t forced_vents() const noexcept override { return forced_vents_.load(std::memory_order_acquire); }

  // Where link events (lost, back, bus summary) go; called on the I/O thread. Default: stderr.
  void set_log_sink(LogSink sink) { log_ = std::move(sink); }
  ModbusBusStats bus_stats() const;  // after close()
  const ModbusRigConfig& config() const noexcept { return config_; }

 protected:
  // Connects every link, writes 0 kPa to every output and reads every monitor once (so a map
  // the device refuses is caught here), then starts the I/O thread. Throws InputError naming
  // the rig file, the link and libmodbus's reason.
  void do_open() override;
  // Writes 0 kPa on every connected link, stops the I/O thread, closes the links.
  void do_close() noexcept override;
  BackendStatus do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept override;
  BackendStatus do_read(ChannelPressures& monitor_kPa, double t_s) noexcept override;
  BackendStatus do_vent() noexcept override;
  BackendStatus do_read_load_cells(std::array<double, kFingerCount>& volts, double t_s) noexcept override;

 private:
  struct Command {
    ChannelPressures kPa{};
    std::int64_t stamp_ns = 0;  // CLOCK_MONOTONIC when the loop wrote it
  };
  struct Monitors {
    ChannelPressures kPa{};
    std::array<double, kFingerCount> cell_volts{};  // the load cells (NaN while a link is down)
  };
  struct LinkState {
    std::unique_ptr<ModbusLink> link;
    bool up = false;
    std::int64_t down_since_ns = 0, next_attempt_ns = 0;
    double backoff_s = 0;
    int attempts = 0;
  };

  void io_thread_main() noexcept;
  void io_cycle(std::int64_t now_ns, double dt_s);
  void mark_down(LinkState& l, std::int64_t now_ns);
  void try_reconnect(LinkState& l, std::int64_t now_ns);
  void write_zeros_everywhere() noexcept;
  void set_fatal(const char* text) noexcept;
  void log(const std::string& line);

  ModbusRigConfig config_;
  LogSink log_;
  std::vector<LinkState> links_;
  std::thread io_thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> linked_{false};
  std::atomic<bool> fatal_{false};
  std::atomic<int> fatal_state_{0};
  std::atomic<std::int64_t> down_since_ns_{0};  // 0 while linked
  std::atomic<std::uint64_t> forced_vents_{0};  // see RigBackend::forced_vents()
  char fatal_text_[256] = {0};                  // written before fatal_ is set (release)

  LatestValue<Command> commands_;   // loop -> I/O thread
  LatestValue<Monitors> monitors_;  // I/O thread -> loop

  // I/O thread state.
  ChannelPressures ramp_kPa_{};  // what the re-engagement ramp allows now
  std::array<bool, kFingerCount> engaging_{};
  bool silenced_ = false;  // the loop fell silent while asking for pressure, and the outputs went to 0
  ChannelWords out_words_{}, mon_words_{}, cell_words_{};
  ChannelWords zero_words_{};  // every output at 0 kPa (not always word 0: signed or offset maps)
  LatencyHistogram cycle_hist_;
  ModbusBusStats stats_;
  std::int64_t start_ns_ = 0;
};

}  // namespace palprig
