#pragma once
// The Modbus section of a rig file: which modules (links) the rig talks to, and per channel
// which holding register takes the regulator command and which register reports its monitor
// voltage, with the raw-count <-> volts <-> kPa scaling of each. Addresses are 0-based, as
// libmodbus takes them (register 40011 in a vendor table is address 10).
//
//   "backend": "modbus",
//   "modbus": {
//     "module": "WAGO 750-352 + 750-559 + 750-459",       (free text, shown in describe())
//     "links": [{"name": "node", "tcp": {"host": "192.168.1.20", "port": 502}, "unit_id": 1}],
//     "io_rate_hz": 500, "response_timeout_ms": 50, "reconnect_backoff_ms": [100, 2000],
//     "setpoint_timeout_ms": 100, "max_outage_s": 2, "io_thread_fifo_priority": 70
//   },
//   "channels": [{"output":  {"register": 0, "raw_full_scale": 32767, "signed": false,
//                             "volts_span": [0, 10], "kPa_per_volt": 10},
//                 "monitor": {"register": 0, "function": "input", "raw_full_scale": 32767,
//                             "volts_span": [0, 10], "kPa_per_volt": 10}}, ...]
//
// The map is validated when the rig file is loaded: a register used twice, a span that cannot
// carry p_max, a link nobody uses, a full scale the signedness cannot hold, ... are refused.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/regulator_scale.hpp"
#include "models/finger_layout.hpp"

namespace palprig {

struct RigConfig;

// Raw register counts <-> volts <-> kPa for one analog register. Unsigned registers carry
// 0..raw_full_scale over volts_span; signed ones (two's complement int16) carry
// -raw_full_scale..+raw_full_scale over it.
struct RegisterScale {
  std::int32_t raw_full_scale = 4095;
  bool is_signed = false;
  double volts_lo = 0.0, volts_hi = 10.0;
  RegulatorScale regulator;

  std::int32_t raw_lo() const noexcept { return is_signed ? -raw_full_scale : 0; }
  // Volts clamped to the span, rounded to the nearest count, encoded as the 16-bit word.
  std::uint16_t word_from_volts(double volts) const noexcept;
  std::uint16_t word_from_kPa(double pressure_kPa) const noexcept {
    return word_from_volts(regulator.volts(pressure_kPa));
  }
  // Decodes the word (sign-extended when signed); counts beyond the full scale are reported as
  // they are (a module over-range reading), not clamped.
  double volts_from_word(std::uint16_t word) const noexcept;
  double kPa_from_word(std::uint16_t word) const noexcept { return regulator.pressure_kPa(volts_from_word(word)); }
};

enum class RegisterKind : std::uint8_t { holding, input };  // FC03/06/16 or FC04

struct ModbusLinkConfig {
  std::string name;
  bool rtu = false;
  std::string host = "127.0.0.1";  // tcp
  int port = 502;
  std::string device;  // rtu: serial device
  int baud = 9600;
  char parity = 'N';
  int data_bits = 8, stop_bits = 1;
  int unit_id = 1;
  std::string endpoint() const;  // "tcp 127.0.0.1:502" or "rtu /dev/ttyUSB0 9600 8N1"
};

struct ModbusRegisterRef {
  std::size_t link = 0;  // index into ModbusRigConfig::links
  int address = 0;       // 0-based
  RegisterKind kind = RegisterKind::holding;
  RegisterScale scale;
};

// Why a Modbus TCP host (name or address) is refused, "" when it is acceptable: DNS syntax
// (RFC 1123 labels; '_' tolerated) or an IPv4/IPv6 literal. Names are resolved (getaddrinfo)
// when the link is made, not here.
std::string modbus_host_refusal(const std::string& host);

struct ModbusChannelMap {
  ModbusRegisterRef output;  // always a holding register
  ModbusRegisterRef monitor;
};

struct ModbusRigConfig {
  std::string source;  // rig file, for messages
  std::string rig_id;
  std::string module;  // free-text description
  std::vector<ModbusLinkConfig> links;
  std::array<ModbusChannelMap, kFingerCount> channels{};
  double io_rate_hz = 500.0;
  double response_timeout_s = 0.05;
  double reconnect_initial_s = 0.1, reconnect_max_s = 2.0;
  double setpoint_timeout_s = 0.1;   // loop silent this long: the bus thread vents on its own
  double max_outage_s = 2.0;         // a link down this long ends the run (backend error); 0: never
  int io_thread_fifo_priority = 70;  // 0: normal scheduling
  double p_max_kPa = 60.0;           // from the rig's safety section
  double slew_kPa_per_s = 2000.0;    // re-engagement ramp after a vent or a reconnect

  // True when the monitor of `channel` reads back its own output register (modules without
  // analog inputs): the simulator then leaves that register as the client wrote it.
  bool monitor_is_readback(std::size_t channel) const noexcept;
};

// Parse and validate the "modbus" section (with the rig file's "channels" array under
// "channels": their "output"/"monitor" objects) of a rig being loaded; load_rig_file calls it
// once and keeps the result in RigConfig::modbus. `rig` gives the file, id and safety limits.
// Throws InputError naming the file and field.
ModbusRigConfig parse_modbus_config(const RigConfig& rig, const nlohmann::json& backend_section);

}  // namespace palprig
