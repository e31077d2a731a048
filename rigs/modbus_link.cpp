#include "rigs/modbus_link.hpp"

#include <modbus.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace palprig {

std::vector<RegisterRun> contiguous_runs(std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  std::vector<RegisterRun> runs;
  for (const auto& [address, channel] : pairs) {
    if (runs.empty() || address != runs.back().start + int(runs.back().channels.size()))
      runs.push_back({address, {}});
    runs.back().channels.push_back(channel);
  }
  return runs;
}

ModbusLink::ModbusLink(const ModbusRigConfig& rig, std::size_t index) : link_(rig.links.at(index)) {
  ctx_ = link_.rtu ? modbus_new_rtu(link_.device.c_str(), link_.baud, link_.parity, link_.data_bits, link_.stop_bits)
                   : modbus_new_tcp(link_.host.c_str(), link_.port);
  if (!ctx_) throw std::runtime_error("modbus link '" + link_.name + "' (" + link_.endpoint() + "): " + modbus_strerror(errno));
  modbus_set_slave(ctx_, link_.unit_id);
  // The I/O thread decides about reconnecting itself (with backoff); libmodbus must not retry
  // or sleep on its own.
  modbus_set_error_recovery(ctx_, MODBUS_ERROR_RECOVERY_NONE);
  const double t = rig.response_timeout_s;
  const auto sec = static_cast<std::uint32_t>(t);
  const auto usec = static_cast<std::uint32_t>(std::lround((t - sec) * 1e6));
  modbus_set_response_timeout(ctx_, sec, usec);
  modbus_set_byte_timeout(ctx_, sec, usec);

  std::vector<std::pair<int, int>> outputs, input_regs, holding_regs;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    const auto& ch = rig.channels[c];
    if (ch.output.link == index) outputs.emplace_back(ch.output.address, int(c));
    if (ch.monitor.link == index)
      (ch.monitor.kind == RegisterKind::input ? input_regs : holding_regs).emplace_back(ch.monitor.address, int(c));
  }
  auto add = [](std::vector<Block>& to, const std::vector<std::pair<int, int>>& pairs, RegisterKind kind) {
    for (const auto& run : contiguous_runs(pairs)) {
      Block b;
      b.start = run.start;
      b.count = int(run.channels.size());
      b.kind = kind;
      for (int k = 0; k < b.count; ++k) b.channel_at[k] = run.channels[k];
      to.push_back(b);
    }
  };
  add(writes_, outputs, RegisterKind::holding);
  add(reads_, input_regs, RegisterKind::input);
  add(reads_, holding_regs, RegisterKind::holding);
}

ModbusLink::~ModbusLink() {
  disconnect();
  if (ctx_) modbus_free(ctx_);
}

bool ModbusLink::fail(const char* what, int address) noexcept {
  const int e = errno;
  // Exception replies (illegal function/address/value, device failure, ...) mean the device is
  // there and refuses this map; anything else (timeout, reset, refused) means the link is down.
  error_kind_ = (e > MODBUS_ENOBASE && e <= EMBXGTAR) ? LinkError::device : LinkError::link;
  if (address >= 0)
    std::snprintf(error_, sizeof error_, "%s register %d: %s", what, address, modbus_strerror(e));
  else
    std::snprintf(error_, sizeof error_, "%s: %s", what, modbus_strerror(e));
  return false;
}

bool ModbusLink::connect() noexcept {
  disconnect();
  if (modbus_connect(ctx_) == -1) return fail("connect", -1);
  connected_ = true;
  error_kind_ = LinkError::none;
  return true;
}

void ModbusLink::disconnect() noexcept {
  if (connected_) modbus_close(ctx_);
  connected_ = false;
}

bool ModbusLink::write_outputs(const ChannelWords& words) noexcept {
  std::uint16_t buf[kFingerCount];
  for (const Block& b : writes_) {
    int rc;
    if (b.count == 1) {
      rc = modbus_write_register(ctx_, b.start, words[b.channel_at[0]]);
    } else {
      for (int k = 0; k < b.count; ++k) buf[k] = words[b.channel_at[k]];
      rc = modbus_write_registers(ctx_, b.start, b.count, buf);
    }
    if (rc == -1) return fail("write holding", b.start);
  }
  return true;
}

bool ModbusLink::read_monitors(ChannelWords& words) noexcept {
  std::uint16_t buf[kFingerCount];
  for (const Block& b : reads_) {
    const int rc = b.kind == RegisterKind::input ? modbus_read_input_registers(ctx_, b.start, b.count, buf)
                                                 : modbus_read_registers(ctx_, b.start, b.count, buf);
    if (rc == -1) return fail(b.kind == RegisterKind::input ? "read input" : "read holding", b.start);
    for (int k = 0; k < b.count; ++k) words[b.channel_at[k]] = buf[k];
  }
  return true;
}

}  // namespace palprig
