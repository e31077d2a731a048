#include "formats/load_cell_config.hpp"

#include <set>

#include "formats/json_file.hpp"
#include "formats/rig_file.hpp"

namespace palprig {

namespace {

std::size_t load_cell_link(const JsonObject& o, const std::vector<ModbusLinkConfig>& links) {
  if (!o.has("link")) {
    if (links.size() == 1) return 0;
    o.fail("link", "the name of one of the " + std::to_string(links.size()) + " Modbus links (several are defined)");
  }
  const std::string name = o.string("link");
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].name == name) return i;
  o.fail("link", "the name of a link in modbus.links, got \"" + name + "\"");
}

std::pair<double, double> volts_span(const JsonObject& o) {
  const auto span = o.numbers("volts_span", -1000, 1000);
  if (span.size() != 2 || !(span[0] < span[1])) o.fail("volts_span", "[low, high] in volts with low < high");
  return {span[0], span[1]};
}

ModbusRegisterRef modbus_input(const JsonObject& o, const ModbusRigConfig& modbus) {
  ModbusRegisterRef r;
  r.link = load_cell_link(o, modbus.links);
  r.address = static_cast<int>(o.integer("register", 0, 65535));
  r.kind =
      o.choice_or("function", "input", {"input", "holding"}) == "input" ? RegisterKind::input : RegisterKind::holding;
  r.scale.is_signed = o.boolean_or("signed", false);
  r.scale.raw_full_scale = static_cast<std::int32_t>(o.integer_or("raw_full_scale", r.scale.raw_full_scale, 1, 65535));
  if (r.scale.is_signed && r.scale.raw_full_scale > 32767)
    o.fail("raw_full_scale",
           "at most 32767 for a signed (int16) register, got " + std::to_string(r.scale.raw_full_scale));
  std::tie(r.scale.volts_lo, r.scale.volts_hi) = volts_span(o);
  o.refuse_unknown();
  return r;
}

}  // namespace

LoadCellConfig parse_load_cell_config(const RigConfig& rig, const nlohmann::json& section) {
  LoadCellConfig cfg;
  const JsonObject o(section, rig.source, "load_cells");
  cfg.per_finger = o.choice("fingers", {"each", "all"}) == "each";
  const auto channels = o.objects("channels");
  const std::size_t want = cfg.per_finger ? kFingerCount : 1;
  if (channels.size() != want)
    o.fail("channels", std::to_string(want) + (want == 1 ? " channel" : " channels") + " with \"fingers\": \"" +
                           (cfg.per_finger ? "each" : "all") + "\", got " + std::to_string(channels.size()));
  std::set<std::pair<std::size_t, int>> used;  // (Modbus link or comedi, channel or register)
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const JsonObject& c = channels[i];
    LoadCellChannel ch;
    ch.calibration.tare_V = c.number_or("tare_V", 0.0, -1000, 1000);
    ch.calibration.N_per_V = c.number("N_per_V", 1e-9, 1e9);
    if (rig.backend == "simulated") {
      if (c.has("input")) c.fail("input", "no input on the simulated rig (its cells are in \"simulated\")");
    } else {
      if (!c.has("input"))
        c.fail("input", rig.backend == "comedi"
                            ? "the analog input the cell is read on: {\"channel\": N, \"volts_span\": [low, high]}"
                            : "the register the cell is read on: {\"register\": N, \"volts_span\": [low, high], ...}");
      const JsonObject in = c.object("input");
      if (rig.backend == "comedi") {
        ch.comedi_channel = static_cast<int>(in.integer("channel", 0, 255));
        std::tie(ch.volts_lo, ch.volts_hi) = volts_span(in);
        in.refuse_unknown();
        for (const auto& m : rig.comedi->monitors)
          if (m.channel == ch.comedi_channel)
            in.fail("channel", "an analog input no regulator monitor uses, got " + std::to_string(ch.comedi_channel));
        if (!used.insert({0, ch.comedi_channel}).second)
          in.fail("channel",
                  "an analog input no other load cell uses, got " + std::to_string(ch.comedi_channel) + " twice");
      } else {
        ch.modbus = modbus_input(in, *rig.modbus);
        for (const auto& m : rig.modbus->channels)
          if (m.monitor.link == ch.modbus->link && m.monitor.address == ch.modbus->address &&
              m.monitor.kind == ch.modbus->kind)
            in.fail("register", "a register no regulator monitor reads, got " + std::to_string(ch.modbus->address));
        for (const auto& m : rig.modbus->channels)
          if (ch.modbus->kind == RegisterKind::holding && m.output.link == ch.modbus->link &&
              m.output.address == ch.modbus->address)
            in.fail("register", "a register that is no regulator's output, got holding register " +
                                    std::to_string(ch.modbus->address));
        if (!used.insert({ch.modbus->link * 2 + (ch.modbus->kind == RegisterKind::input), ch.modbus->address}).second)
          in.fail("register",
                  "a register no other load cell reads, got " + std::to_string(ch.modbus->address) + " twice");
      }
    }
    c.refuse_unknown();
    cfg.channels.push_back(ch);
  }
  if (o.has("simulated")) {
    if (rig.backend != "simulated")
      o.fail("simulated", "nothing on a \"" + rig.backend + "\" rig (its cells are real)");
    const JsonObject s = o.object("simulated");
    SimulatedLoadCellParams& p = cfg.simulated;
    p.stiffness_N_per_mm = s.number_or("stiffness_N_per_mm", p.stiffness_N_per_mm, 1e-6, 1e6);
    p.tare_V = s.number_or("tare_V", p.tare_V, -100, 100);
    p.N_per_V = s.number_or("N_per_V", p.N_per_V, 1e-6, 1e6);
    p.noise_sd_V = s.number_or("noise_sd_V", p.noise_sd_V, 0, 100);
    p.max_V = s.number_or("max_V", p.max_V, 1e-3, 1000);
    p.seed = static_cast<std::uint64_t>(s.integer_or("seed", static_cast<std::int64_t>(p.seed), 0, INT64_MAX));
    if (p.tare_V >= p.max_V) s.fail("tare_V", "below max_V (" + std::to_string(p.max_V) + " V)");
    s.refuse_unknown();
  }
  o.refuse_unknown();
  return cfg;
}

}  // namespace palprig
