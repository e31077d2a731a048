#include "rigs/modbus_link.hpp"

#include <arpa/inet.h>
#include <modbus.h>
#include <netdb.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/input_error.hpp"

namespace palprig {

std::vector<RegisterRun> contiguous_runs(std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  std::vector<RegisterRun> runs;
  for (const auto& [address, channel] : pairs) {
    if (runs.empty() || address != runs.back().start + int(runs.back().channels.size())) runs.push_back({address, {}});
    runs.back().channels.push_back(channel);
  }
  return runs;
}

NumericHost resolve_modbus_host(const std::string& host) {
  NumericHost out;
  if (const std::string why = modbus_host_refusal(host); !why.empty()) {
    out.error = why;
    return out;
  }
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int rc = getaddrinfo(host.c_str(), nullptr, &hints, &found);
  if (rc != 0 || !found) {
    out.error = std::string("a host name that resolves to an address (getaddrinfo: ") +
                (rc == EAI_SYSTEM ? std::strerror(errno) : gai_strerror(rc)) + "), got \"" + host + "\"";
    return out;
  }
  // IPv4 first: modbus_new_tcp takes a dotted quad; an IPv6-only name goes through
  // modbus_new_tcp_pi with the numeric address.
  const addrinfo* pick = nullptr;
  for (const addrinfo* a = found; a && !pick; a = a->ai_next)
    if (a->ai_family == AF_INET) pick = a;
  for (const addrinfo* a = found; a && !pick; a = a->ai_next)
    if (a->ai_family == AF_INET6) pick = a;
  char text[INET6_ADDRSTRLEN] = {0};
  if (pick && pick->ai_family == AF_INET)
    inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(pick->ai_addr)->sin_addr, text, sizeof text);
  else if (pick)
    inet_ntop(AF_INET6, &reinterpret_cast<const sockaddr_in6*>(pick->ai_addr)->sin6_addr, text, sizeof text);
  if (pick) out.ipv6 = pick->ai_family == AF_INET6;
  freeaddrinfo(found);
  if (text[0] == '\0')
    out.error = "a host name with an IPv4 or IPv6 address, got \"" + host + "\"";
  else
    out.address = text;
  return out;
}

ModbusLink::ModbusLink(const ModbusRigConfig& rig, std::size_t index) : link_(rig.links.at(index)) {
  if (link_.rtu) {
    ctx_ = modbus_new_rtu(link_.device.c_str(), link_.baud, link_.parity, link_.data_bits, link_.stop_bits);
  } else {
    // libmodbus's modbus_new_tcp takes only a numeric IPv4 address of at most 15 characters (it
    // truncates a longer string and prints to stderr); names are resolved here, once, before
    // anything is opened, and a name that does not resolve is refused like a bad file field.
    const NumericHost numeric = resolve_modbus_host(link_.host);
    if (!numeric.error.empty())
      throw InputError(rig.source, "modbus.links[" + std::to_string(index) + "].tcp.host", numeric.error);
    resolved_host_ = numeric.address;
    ctx_ = numeric.ipv6 ? modbus_new_tcp_pi(numeric.address.c_str(), std::to_string(link_.port).c_str())
                        : modbus_new_tcp(numeric.address.c_str(), link_.port);
  }
  if (!ctx_) throw Error("modbus link '" + link_.name + "' (" + link_.endpoint() + "): " + modbus_strerror(errno));
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

void ModbusLink::plan_load_cells(const LoadCellConfig& cells, std::size_t index) {
  cell_reads_.clear();
  std::vector<std::pair<int, int>> input_regs, holding_regs;
  for (std::size_t i = 0; i < cells.channels.size(); ++i) {
    const auto& ref = cells.channels[i].modbus;
    if (ref && ref->link == index)
      (ref->kind == RegisterKind::input ? input_regs : holding_regs).emplace_back(ref->address, int(i));
  }
  for (const auto& [pairs, kind] :
       {std::pair{input_regs, RegisterKind::input}, std::pair{holding_regs, RegisterKind::holding}})
    for (const auto& run : contiguous_runs(pairs)) {
      Block b;
      b.start = run.start;
      b.count = int(run.channels.size());
      b.kind = kind;
      for (int k = 0; k < b.count; ++k) b.channel_at[k] = run.channels[k];
      cell_reads_.push_back(b);
    }
}

bool ModbusLink::read_load_cells(ChannelWords& words) noexcept {
  std::uint16_t buf[kFingerCount];
  for (const Block& b : cell_reads_) {
    const int rc = b.kind == RegisterKind::input ? modbus_read_input_registers(ctx_, b.start, b.count, buf)
                                                 : modbus_read_registers(ctx_, b.start, b.count, buf);
    if (rc == -1)
      return fail(b.kind == RegisterKind::input ? "read load cell input" : "read load cell holding", b.start);
    for (int k = 0; k < b.count; ++k) words[b.channel_at[k]] = buf[k];
  }
  return true;
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
