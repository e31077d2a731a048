#include "formats/modbus_register_map.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "formats/json_file.hpp"
#include "core/input_error.hpp"
#include "formats/rig_file.hpp"

namespace palprig {

std::uint16_t RegisterScale::word_from_volts(double volts) const noexcept {
  if (!std::isfinite(volts)) volts = volts_lo;  // never reached with validated setpoints; safe side
  volts = std::clamp(volts, volts_lo, volts_hi);
  const double counts =
      double(raw_lo()) + (volts - volts_lo) / (volts_hi - volts_lo) * double(raw_full_scale - raw_lo());
  const auto raw = static_cast<std::int32_t>(std::lround(std::clamp(counts, double(raw_lo()), double(raw_full_scale))));
  return static_cast<std::uint16_t>(raw);  // two's complement for negative counts
}

double RegisterScale::volts_from_word(std::uint16_t word) const noexcept {
  const std::int32_t raw = is_signed ? std::int32_t(std::int16_t(word)) : std::int32_t(word);
  return volts_lo + double(raw - raw_lo()) / double(raw_full_scale - raw_lo()) * (volts_hi - volts_lo);
}

std::string ModbusLinkConfig::endpoint() const {
  // Host and device come from a file: escaped, so no message carries a control character.
  std::ostringstream s;
  if (rtu)
    s << "rtu " << printable_excerpt(device, 120) << " " << baud << " " << data_bits << parity << stop_bits;
  else
    s << "tcp " << printable_excerpt(host, 120) << ":" << port;
  return s.str();
}

std::string modbus_host_refusal(const std::string& host) {
  std::string expected =  // not const: returned by move
      "a host name (letters, digits, '-' and '.', labels of at most 63 and at most 253 characters) or an IPv4 or "
      "IPv6 address, got \"" +
      host + "\"";
  if (host.empty() || host.size() > 253) return expected;
  in_addr v4{};
  in6_addr v6{};
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1 || inet_pton(AF_INET6, host.c_str(), &v6) == 1) return "";
  std::size_t label = 0;
  for (std::size_t i = 0; i < host.size(); ++i) {
    const char c = host[i];
    if (c == '.') {
      if (label == 0) return expected;  // empty label (".." or a leading dot)
      label = 0;
      continue;
    }
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    if (!ok || ++label > 63) return expected;
    if (c == '-' && (label == 1 || i + 1 == host.size() || host[i + 1] == '.')) return expected;
  }
  return "";
}

bool ModbusRigConfig::monitor_is_readback(std::size_t c) const noexcept {
  const auto& ch = channels[c];
  return ch.monitor.kind == RegisterKind::holding && ch.monitor.link == ch.output.link &&
         ch.monitor.address == ch.output.address;
}

namespace {

ModbusLinkConfig parse_link(const JsonObject& o) {
  ModbusLinkConfig l;
  l.name = o.string("name");
  if (l.name.empty()) o.fail("name", "a non-empty link name");
  const bool tcp = o.has("tcp"), rtu = o.has("rtu");
  if (tcp == rtu) o.fail("tcp", "exactly one of \"tcp\" {host, port} or \"rtu\" {device, baud, ...}");
  if (tcp) {
    const JsonObject t = o.object("tcp");
    l.host = t.string("host");
    if (const std::string why = modbus_host_refusal(l.host); !why.empty()) t.fail("host", why);
    l.port = static_cast<int>(t.integer("port", 1, 65535));
    t.refuse_unknown();
  } else {
    const JsonObject r = o.object("rtu");
    l.rtu = true;
    l.device = r.string("device");
    if (l.device.empty()) r.fail("device", "a serial device path such as /dev/ttyUSB0");
    l.baud = static_cast<int>(r.integer_or("baud", 9600, 300, 4000000));
    l.parity = r.choice_or("parity", "N", {"N", "E", "O"})[0];
    l.data_bits = static_cast<int>(r.integer_or("data_bits", 8, 5, 8));
    l.stop_bits = static_cast<int>(r.integer_or("stop_bits", 1, 1, 2));
    r.refuse_unknown();
  }
  // 0 is broadcast (no reply); 248-255 are reserved, except 255 which TCP gateways accept.
  l.unit_id = static_cast<int>(o.integer_or("unit_id", 1, 1, 255));
  o.refuse_unknown();
  return l;
}

std::size_t find_link(const JsonObject& o, const std::vector<ModbusLinkConfig>& links) {
  if (!o.has("link")) {
    if (links.size() == 1) return 0;
    o.fail("link", "the name of one of the " + std::to_string(links.size()) + " links (several are defined)");
  }
  const std::string name = o.string("link");
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].name == name) return i;
  o.fail("link", "the name of a link in modbus.links, got \"" + name + "\"");
}

// `base` supplies the defaults of a monitor (the output's scaling) so a monitor on the same
// kind of module needs only its register.
ModbusRegisterRef parse_register(const JsonObject& o, const std::vector<ModbusLinkConfig>& links, bool is_monitor,
                                 const ModbusRegisterRef* base) {
  ModbusRegisterRef r;
  if (base) r.scale = base->scale;
  r.link = find_link(o, links);
  r.address = static_cast<int>(o.integer("register", 0, 65535));
  r.kind = RegisterKind::holding;
  if (is_monitor)
    r.kind =
        o.choice_or("function", "input", {"input", "holding"}) == "input" ? RegisterKind::input : RegisterKind::holding;
  RegisterScale& s = r.scale;
  s.is_signed = o.boolean_or("signed", s.is_signed);
  s.raw_full_scale = static_cast<std::int32_t>(o.integer_or("raw_full_scale", s.raw_full_scale, 1, 65535));
  if (s.is_signed && s.raw_full_scale > 32767)
    o.fail("raw_full_scale", "at most 32767 for a signed (int16) register, got " + std::to_string(s.raw_full_scale));
  if (o.has("volts_span")) {
    const auto span = o.numbers("volts_span", -1000, 1000);
    if (span.size() != 2 || !(span[0] < span[1]))
      o.fail("volts_span", "[low, high] in volts with low < high (the volts at the lowest and highest raw count)");
    s.volts_lo = span[0];
    s.volts_hi = span[1];
  } else if (!base) {
    o.fail("volts_span", "[low, high] in volts (field is missing)");
  }
  if (base) s.regulator = base->scale.regulator;
  s.regulator.kPa_per_volt =
      base ? o.number_or("kPa_per_volt", s.regulator.kPa_per_volt, 1e-6, 1e6) : o.number("kPa_per_volt", 1e-6, 1e6);
  s.regulator.volts_at_0_kPa = o.number_or("volts_at_0_kPa", base ? s.regulator.volts_at_0_kPa : 0.0, -1000, 1000);
  o.refuse_unknown();
  return r;
}

std::string volts_text(double v) {
  std::ostringstream s;
  s << v << " V";
  return s.str();
}

}  // namespace

ModbusRigConfig parse_modbus_config(const RigConfig& rig, const nlohmann::json& backend_section) {
  ModbusRigConfig cfg;
  cfg.source = rig.source;
  cfg.rig_id = rig.id;
  cfg.p_max_kPa = rig.safety.p_max_kPa;
  cfg.slew_kPa_per_s = rig.safety.slew_kPa_per_s;

  nlohmann::json section = backend_section;
  if (!section.is_object()) throw InputError(rig.source, "modbus", "an object with the Modbus links");
  const nlohmann::json channels = section.contains("channels") ? section["channels"] : nlohmann::json();
  section.erase("channels");
  const JsonObject m(section, rig.source, "modbus");
  cfg.module = m.string_or("module", "");
  for (const auto& l : m.objects("links")) cfg.links.push_back(parse_link(l));
  if (cfg.links.empty()) m.fail("links", "at least one link");
  for (std::size_t i = 0; i < cfg.links.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (cfg.links[i].name == cfg.links[j].name)
        m.fail("links[" + std::to_string(i) + "].name",
               "a name no other link has, got \"" + cfg.links[i].name + "\" twice");
  cfg.io_rate_hz = m.number_or("io_rate_hz", cfg.io_rate_hz, 1, 5000);
  cfg.response_timeout_s = m.number_or("response_timeout_ms", cfg.response_timeout_s * 1e3, 1, 10000) / 1e3;
  if (m.has("reconnect_backoff_ms")) {
    const auto b = m.numbers("reconnect_backoff_ms", 1, 600000);
    if (b.size() != 2 || b[0] > b[1])
      m.fail("reconnect_backoff_ms", "[first, longest] wait in ms with first <= longest");
    cfg.reconnect_initial_s = b[0] / 1e3;
    cfg.reconnect_max_s = b[1] / 1e3;
  }
  cfg.setpoint_timeout_s = m.number_or("setpoint_timeout_ms", cfg.setpoint_timeout_s * 1e3, 1, 60000) / 1e3;
  cfg.max_outage_s = m.number_or("max_outage_s", cfg.max_outage_s, 0, 86400);
  cfg.io_thread_fifo_priority =
      static_cast<int>(m.integer_or("io_thread_fifo_priority", cfg.io_thread_fifo_priority, 0, 98));
  m.refuse_unknown();

  if (!channels.is_array())
    throw InputError(
        rig.source, "channels",
        "an array of " + std::to_string(kFingerCount) + " channel objects with \"output\" and \"monitor\" registers");
  const nlohmann::json channels_doc = {{"channels", channels}};  // JsonObject keeps a pointer: keep it alive
  const JsonObject root(channels_doc, rig.source, "");
  const auto ch = root.objects("channels");  // rig_file already checked the count
  std::set<std::size_t> used_links;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    ch[i].has("plant");  // read by the rig file (the simulator's plant for this channel)
    ModbusChannelMap& c = cfg.channels[i];
    c.output = parse_register(ch[i].object("output"), cfg.links, false, nullptr);
    c.monitor = parse_register(ch[i].object("monitor"), cfg.links, true, &c.output);
    ch[i].refuse_unknown();
    used_links.insert(c.output.link);
    used_links.insert(c.monitor.link);

    const JsonObject out = ch[i].object("output");
    const RegisterScale& s = c.output.scale;
    const double v0 = s.regulator.volts(0.0), vmax = s.regulator.volts(cfg.p_max_kPa);
    const double lo = std::min(v0, vmax), hi = std::max(v0, vmax);
    if (lo < s.volts_lo - 1e-9 || hi > s.volts_hi + 1e-9)
      out.fail("volts_span", "a span that carries 0..p_max (0 kPa = " + volts_text(v0) + ", p_max " +
                                 std::to_string(cfg.p_max_kPa) + " kPa = " + volts_text(vmax) + "), got [" +
                                 volts_text(s.volts_lo) + ", " + volts_text(s.volts_hi) + "]");
  }
  // No register may be commanded twice, and no monitor may read another channel's command.
  std::map<std::pair<std::size_t, int>, std::size_t> outputs;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const auto key = std::make_pair(cfg.channels[i].output.link, cfg.channels[i].output.address);
    if (auto it = outputs.find(key); it != outputs.end())
      ch[i].object("output").fail("register", "a holding register no other channel uses, got " +
                                                  std::to_string(key.second) + " (also channel " +
                                                  std::to_string(it->second + 1) + "'s output on link \"" +
                                                  cfg.links[key.first].name + "\")");
    outputs[key] = i;
  }
  std::map<std::tuple<std::size_t, int, RegisterKind>, std::size_t> monitors;
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    const auto& mon = cfg.channels[i].monitor;
    if (mon.kind == RegisterKind::holding) {
      const auto it = outputs.find({mon.link, mon.address});
      if (it != outputs.end() && it->second != i)
        ch[i].object("monitor").fail(
            "register", "a register that is not another channel's output, got holding register " +
                            std::to_string(mon.address) + " (channel " + std::to_string(it->second + 1) + "'s output)");
    }
    const auto key = std::make_tuple(mon.link, mon.address, mon.kind);
    if (auto it = monitors.find(key); it != monitors.end())
      ch[i].object("monitor").fail("register", "a register no other channel's monitor reads, got " +
                                                   std::to_string(mon.address) + " (also channel " +
                                                   std::to_string(it->second + 1) + "'s monitor)");
    monitors[key] = i;
  }
  for (std::size_t l = 0; l < cfg.links.size(); ++l)
    if (!used_links.count(l))
      m.fail("links[" + std::to_string(l) + "]",
             "a link some channel uses (\"" + cfg.links[l].name + "\" is used by none)");
  return cfg;
}

}  // namespace palprig
