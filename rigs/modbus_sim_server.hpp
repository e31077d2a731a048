#pragma once
// ModbusSimServer: the simulated rig served as a real Modbus TCP server (libmodbus), so the
// whole network path (ModbusRig, its I/O thread, the sockets, the register map) runs without
// hardware. `palprig sim-rig` wraps it; the tests and the Modbus benchmark start it in process.
//
// Each link of the rig's register map gets its own listening socket (a real module per link)
// and its own register space; several clients may connect to each. A plant thread steps the
// three PneumaticPlant channels in wall-clock time at 1 kHz: it decodes each channel's output
// holding register into a command (the same scaling the client used to encode it) and encodes
// the plant's monitor pressure into the monitor register. Like a real module's communication
// watchdog, an optional timeout sets the outputs of a link nobody talks to back to 0 kPa.
// A link may also be served as Modbus RTU on a pseudo-terminal, so the RTU client path (framing,
// CRC, unit id) runs without a serial adapter.
#include <array>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "formats/load_cell_config.hpp"
#include "formats/modbus_register_map.hpp"
#include "models/load_cell.hpp"
#include "models/pneumatic_plant.hpp"

typedef struct _modbus modbus_t;
typedef struct _modbus_mapping_t modbus_mapping_t;

namespace palprig {

struct ListenAddress {
  std::string host = "127.0.0.1";
  int port = 0;      // 0: an ephemeral port, see ModbusSimServer::port()
  bool pty = false;  // Modbus RTU on a new pseudo-terminal instead (see ModbusSimServer::pty_path())
};

// "HOST:PORT" or "pty" -> ListenAddress; throws BadInput with the reason.
ListenAddress parse_listen_address(const std::string& text);

class ModbusSimServer {
 public:
  using LogSink = std::function<void(const std::string&)>;

  ModbusSimServer(ModbusRigConfig map, const std::array<PlantParams, kFingerCount>& plants);
  ~ModbusSimServer();
  ModbusSimServer(const ModbusSimServer&) = delete;
  ModbusSimServer& operator=(const ModbusSimServer&) = delete;

  // Options, before start().
  void set_log_sink(LogSink sink) { log_ = std::move(sink); }
  // Every write to an output register, as CSV rows "t_s,channel,word,kPa,mono_ns" (t_s since
  // start; mono_ns the arrival on CLOCK_MONOTONIC, the clock palprig's loop and pen reader use,
  // so end-to-end latency can be measured across processes on one machine).
  void set_write_log(const std::filesystem::path& path);
  void set_watchdog_s(double seconds) { watchdog_s_ = seconds; }
  // The rig's load cells on Modbus registers: each is simulated from its channel's
  // tare and gain, with `load_N` resting on it (a calibration weight; 0: nothing), and its
  // register kept up to date by the plant thread. Before start().
  void set_load_cells(const LoadCellConfig& cells, double load_N);

  // Listen on one address per link (in the map's link order) and start serving. Throws
  // Error with the address and the system's reason when a socket cannot be bound.
  void start(const std::vector<ListenAddress>& listen);
  void stop() noexcept;
  int port(std::size_t link) const { return links_.at(link)->port; }
  // The serial device a Modbus RTU client opens for a link served on a pty (e.g. /dev/pts/3).
  const std::string& pty_path(std::size_t link) const { return links_.at(link)->pty_path; }

  // Observations (any thread).
  std::array<std::uint16_t, kFingerCount> output_words() const;
  double plant_output_kPa(std::size_t channel) const;
  std::uint64_t requests() const noexcept { return requests_.load(std::memory_order_relaxed); }
  int clients() const noexcept { return clients_.load(std::memory_order_relaxed); }

 private:
  struct Link {
    ListenAddress address;
    int port = 0;
    modbus_t* ctx = nullptr;
    modbus_mapping_t* mapping = nullptr;
    int listen_fd = -1;
    int pty_master = -1, pty_slave = -1;  // RTU on a pty: we serve the master side
    std::string pty_path;
    std::thread thread;
    std::int64_t last_request_ns = 0;
    bool watchdog_tripped = false;
  };
  void serve(Link& link, std::size_t index) noexcept;
  void serve_rtu(Link& link, std::size_t index) noexcept;
  void handle(Link& link, std::size_t index, const std::uint8_t* query, int length) noexcept;
  void step_plants() noexcept;
  std::uint16_t* output_register(std::size_t channel) const noexcept;
  std::uint16_t* monitor_register(std::size_t channel) const noexcept;
  std::uint16_t* register_of(const ModbusRegisterRef& ref) const noexcept;
  void after_write(std::size_t link, const std::uint8_t* query, int header_length) noexcept;
  void log(const std::string& line);

  ModbusRigConfig map_;
  std::array<PneumaticPlant, kFingerCount> plants_;
  std::vector<ModbusRegisterRef> cell_registers_;
  std::vector<SimulatedLoadCell> cells_;
  double cell_load_N_ = 0;
  std::vector<std::unique_ptr<Link>> links_;
  std::thread plant_thread_;
  mutable std::mutex mutex_;  // registers and plants: held for one reply or one plant step
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> requests_{0};
  std::atomic<int> clients_{0};
  double watchdog_s_ = 0;
  std::FILE* write_log_ = nullptr;
  std::int64_t start_ns_ = 0, last_step_ns_ = 0;
  LogSink log_;
};

}  // namespace palprig
