#include "formats/comedi_config.hpp"

#include <algorithm>
#include <sstream>

#include "formats/json_file.hpp"
#include "formats/rig_file.hpp"

namespace palprig {

namespace {

ComediChannelSpec parse_spec(const JsonObject& o) {
  ComediChannelSpec s;
  s.channel = static_cast<int>(o.integer("channel", 0, 1023));
  const auto span = o.numbers("volts_span", -1000, 1000);
  if (span.size() != 2 || !(span[0] < span[1])) o.fail("volts_span", "[low, high] in volts with low < high");
  s.volts_lo = span[0];
  s.volts_hi = span[1];
  s.regulator.kPa_per_volt = o.number("kPa_per_volt", 1e-6, 1e6);
  s.regulator.volts_at_0_kPa = o.number_or("volts_at_0_kPa", 0.0, -1000, 1000);
  o.refuse_unknown();
  return s;
}

}  // namespace

ComediRigConfig parse_comedi_config(const RigConfig& rig, const nlohmann::json& backend_section) {
  ComediRigConfig cfg;
  cfg.source = rig.source;
  cfg.rig_id = rig.id;
  cfg.p_max_kPa = rig.safety.p_max_kPa;
  nlohmann::json section = backend_section;
  if (!section.is_object()) throw InputError(rig.source, "comedi", "an object with the DAQ device");
  const nlohmann::json channels = section.contains("channels") ? section["channels"] : nlohmann::json();
  section.erase("channels");
  const JsonObject c(section, rig.source, "comedi");
  cfg.device = c.string("device");
  if (cfg.device.empty()) c.fail("device", "a comedi device path such as /dev/comedi0");
  cfg.ao_subdevice = static_cast<int>(c.integer_or("ao_subdevice", -1, -1, 255));
  cfg.ai_subdevice = static_cast<int>(c.integer_or("ai_subdevice", -1, -1, 255));
  const std::string cal = c.choice_or("calibration", "auto", {"auto", "soft", "hard"});
  cfg.calibration = cal == "soft"   ? ComediCalibration::soft
                    : cal == "hard" ? ComediCalibration::hard
                                    : ComediCalibration::automatic;
  cfg.calibration_file = c.string_or("calibration_file", "");
  if (!cfg.calibration_file.empty() && cfg.calibration == ComediCalibration::hard)
    c.fail("calibration_file", "no file with \"calibration\": \"hard\" (files are for soft calibration)");
  const std::string ref = c.choice_or("ai_reference", "ground", {"ground", "common", "differential", "other"});
  cfg.ai_reference = ref == "common"         ? ComediReference::common
                     : ref == "differential" ? ComediReference::differential
                     : ref == "other"        ? ComediReference::other
                                             : ComediReference::ground;
  c.refuse_unknown();

  if (!channels.is_array())
    throw InputError(rig.source, "channels",
                     "an array of " + std::to_string(kFingerCount) +
                         " channel objects with \"output\" and \"monitor\" DAQ channels");
  const nlohmann::json channels_doc = {{"channels", channels}};
  const JsonObject root(channels_doc, rig.source, "");
  const auto ch = root.objects("channels");
  for (std::size_t i = 0; i < kFingerCount; ++i) {
    ch[i].has("plant");
    const JsonObject out = ch[i].object("output");
    cfg.outputs[i] = parse_spec(out);
    cfg.monitors[i] = parse_spec(ch[i].object("monitor"));
    ch[i].refuse_unknown();
    const ComediChannelSpec& s = cfg.outputs[i];
    const double v0 = s.regulator.volts(0.0), vmax = s.regulator.volts(cfg.p_max_kPa);
    if (std::min(v0, vmax) < s.volts_lo - 1e-9 || std::max(v0, vmax) > s.volts_hi + 1e-9) {
      std::ostringstream msg;
      msg << "a span that carries 0..p_max (0 kPa = " << v0 << " V, p_max " << cfg.p_max_kPa << " kPa = " << vmax
          << " V), got [" << s.volts_lo << " V, " << s.volts_hi << " V]";
      out.fail("volts_span", msg.str());
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (cfg.outputs[j].channel == cfg.outputs[i].channel)
        out.fail("channel", "an analog output no other finger uses, got " + std::to_string(cfg.outputs[i].channel) +
                                " (also finger " + std::to_string(j + 1) + "'s)");
      if (cfg.monitors[j].channel == cfg.monitors[i].channel)
        ch[i].object("monitor").fail("channel", "an analog input no other finger uses, got " +
                                                    std::to_string(cfg.monitors[i].channel) + " (also finger " +
                                                    std::to_string(j + 1) + "'s)");
    }
  }
  return cfg;
}

}  // namespace palprig
