#pragma once
// ModbusLink: one libmodbus connection (TCP or RTU) to one module, and the few transactions a
// bus cycle needs, planned once: the channels' output registers on this link grouped into
// contiguous blocks (one FC16 per block, FC06 for a lone register) and their monitor registers
// grouped per function (one FC04 or FC03 per block). Used by the ModbusRig's I/O thread and by
// the benchmark; never by the loop thread.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/load_cell_config.hpp"
#include "formats/modbus_register_map.hpp"

typedef struct _modbus modbus_t;

namespace palprig {

using ChannelWords = std::array<std::uint16_t, kFingerCount>;

enum class LinkError { none, link, device };  // link: timeout/reset/refused; device: exception reply

// A TCP host resolved (getaddrinfo) to the numeric address libmodbus is given: IPv4 when the
// name has one, else IPv6. error: what was expected (the host escaped by the caller's message),
// "" on success. Validated first (modbus_host_refusal).
struct NumericHost {
  std::string address;
  bool ipv6 = false;
  std::string error;
};
NumericHost resolve_modbus_host(const std::string& host);

class ModbusLink {
 public:
  // Creates the libmodbus context (no I/O yet). Throws Error when libmodbus refuses the parameters.
  ModbusLink(const ModbusRigConfig& rig, std::size_t link_index);
  ~ModbusLink();
  ModbusLink(const ModbusLink&) = delete;
  ModbusLink& operator=(const ModbusLink&) = delete;

  bool connect() noexcept;
  void disconnect() noexcept;
  bool connected() const noexcept { return connected_; }

  // Write the output words of this link's channels (indexed by channel; other entries ignored).
  bool write_outputs(const ChannelWords& words) noexcept;
  // Read this link's monitor words into `words` (entries of other channels untouched).
  bool read_monitors(ChannelWords& words) noexcept;
  // The load cells read on this link: planned once before connecting, then read
  // each bus cycle into `words` indexed by cell (entries of cells on other links untouched).
  void plan_load_cells(const LoadCellConfig& cells, std::size_t link_index);
  bool read_load_cells(ChannelWords& words) noexcept;
  bool has_load_cells() const noexcept { return !cell_reads_.empty(); }

  // Why the last call failed: libmodbus's text, and whether the device answered with an
  // exception (a map the device refuses) rather than the link failing.
  const char* last_error() const noexcept { return error_; }
  LinkError last_error_kind() const noexcept { return error_kind_; }
  const ModbusLinkConfig& config() const noexcept { return link_; }
  // The numeric address a TCP link connects to ("" for RTU).
  const std::string& resolved_host() const noexcept { return resolved_host_; }
  bool has_outputs() const noexcept { return !writes_.empty(); }
  bool has_monitors() const noexcept { return !reads_.empty(); }
  std::size_t transactions_per_cycle() const noexcept { return writes_.size() + reads_.size() + cell_reads_.size(); }

 private:
  struct Block {
    int start = 0, count = 0;
    RegisterKind kind = RegisterKind::holding;
    std::array<int, kFingerCount> channel_at{};  // channel of start+k, k < count
  };
  bool fail(const char* what, int address) noexcept;

  ModbusLinkConfig link_;
  std::string resolved_host_;
  modbus_t* ctx_ = nullptr;
  bool connected_ = false;
  std::vector<Block> writes_, reads_, cell_reads_;
  char error_[200] = {0};
  LinkError error_kind_ = LinkError::none;
};

// Group (address, channel) pairs into runs of consecutive addresses. Exposed for tests.
struct RegisterRun {
  int start = 0;
  std::vector<int> channels;  // channel of start, start+1, ...
};
std::vector<RegisterRun> contiguous_runs(std::vector<std::pair<int, int>> address_channel);

}  // namespace palprig
