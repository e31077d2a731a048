#include "formats/rig_file.hpp"

#include "formats/json_file.hpp"
#include "formats/comedi_config.hpp"
#include "formats/modbus_register_map.hpp"

namespace palprig {

PlantParams parse_plant(const JsonObject& o, const PlantParams& base) {
  PlantParams p = base;
  p.dead_time_s = o.number_or("dead_time_s", p.dead_time_s, 0, 1);
  p.time_constant_s = o.number_or("time_constant_s", p.time_constant_s, 0, 10);
  p.slew_kPa_per_s = o.number_or("slew_kPa_per_s", p.slew_kPa_per_s, 1e-3, 1e6);
  p.min_kPa = o.number_or("min_kPa", p.min_kPa, 0, 1000);
  p.max_kPa = o.number_or("max_kPa", p.max_kPa, 0, 1000);
  p.hysteresis_kPa = o.number_or("hysteresis_kPa", p.hysteresis_kPa, 0, 100);
  p.noise_sd_kPa = o.number_or("noise_sd_kPa", p.noise_sd_kPa, 0, 100);
  p.seed = static_cast<std::uint64_t>(o.integer_or("seed", static_cast<std::int64_t>(p.seed), 0, INT64_MAX));
  // A regulator that is not symmetric (each key absent: the symmetric regulator above).
  if (o.has("hysteresis_rising_kPa")) p.hysteresis_rising_kPa = o.number("hysteresis_rising_kPa", 0, 100);
  if (o.has("hysteresis_falling_kPa")) p.hysteresis_falling_kPa = o.number("hysteresis_falling_kPa", 0, 100);
  if (o.has("exhaust_time_constant_s")) p.exhaust_time_constant_s = o.number("exhaust_time_constant_s", 0, 10);
  p.exhaust_lag_factor_at_0 = o.number_or("exhaust_lag_factor_at_0", p.exhaust_lag_factor_at_0, 1, 100);
  p.exhaust_lag_scale_kPa = o.number_or("exhaust_lag_scale_kPa", p.exhaust_lag_scale_kPa, 0.01, 1000);
  p.gain_saturation_kPa = o.number_or("gain_saturation_kPa", p.gain_saturation_kPa, 0, 10000);
  if (p.gain_saturation_kPa > 0 && p.gain_saturation_kPa < 1)
    o.fail("gain_saturation_kPa", "0 (a linear gain) or a saturation pressure of at least 1 kPa");
  if (p.min_kPa >= p.max_kPa) o.fail("max_kPa", "a value above min_kPa");
  o.refuse_unknown();
  return p;
}

static RigConfig parse_rig(const nlohmann::json& doc, const std::string& file) {
  RigConfig rig;
  rig.source = file;
  JsonObject root(doc, file, "");
  root.require_version(kRigFileVersion);
  rig.id = root.string("id");
  if (rig.id.empty()) root.fail("id", "a non-empty rig id");
  rig.backend = root.choice_or("backend", "simulated", {"simulated", "modbus", "comedi"});
  if (root.has("safety")) {
    const JsonObject s = root.object("safety");
    rig.safety.p_max_kPa = s.number("p_max_kPa", 1, 1000);
    rig.safety.slew_kPa_per_s = s.number_or("slew_kPa_per_s", rig.safety.slew_kPa_per_s, 1, 1e6);
    rig.safety.max_input_age_s = s.number_or("max_input_age_s", rig.safety.max_input_age_s, 1e-3, 60);
    rig.safety.max_consecutive_overruns =
        static_cast<int>(s.integer_or("max_consecutive_overruns", rig.safety.max_consecutive_overruns, 1, 1000000));
    rig.safety.max_lost_time_s = s.number_or("max_lost_time_s", rig.safety.max_lost_time_s, 1e-3, 10);
    s.refuse_unknown();
  }
  if (root.has("fingers")) {
    const JsonObject f = root.object("fingers");
    rig.layout.spacing_mm = f.number_or("spacing_mm", rig.layout.spacing_mm, 1, 200);
    rig.layout.orientation_deg = f.number_or("orientation_deg", rig.layout.orientation_deg, -360, 360);
    rig.contact_force_N = f.number_or("contact_force_N", rig.contact_force_N, 0, 100);
    f.refuse_unknown();
  }
  if (root.has("tablet")) rig.tablet = parse_tablet_config(root.object("tablet"));
  PlantParams base;
  if (root.has("plant")) base = parse_plant(root.object("plant"), base);
  rig.plants.fill(base);
  for (std::size_t i = 0; i < kFingerCount; ++i) rig.plants[i].seed = base.seed + i;
  if (root.has("channels")) {
    const auto ch = root.objects("channels");
    if (ch.size() != kFingerCount)
      root.fail("channels",
                "exactly " + std::to_string(kFingerCount) + " channel objects, got " + std::to_string(ch.size()));
    for (std::size_t i = 0; i < kFingerCount; ++i) {
      if (ch[i].has("plant")) rig.plants[i] = parse_plant(ch[i].object("plant"), rig.plants[i]);
      if (rig.backend != "simulated") {
        // Backend-specific channel fields (register map, DAQ channel) are validated by the backend.
        continue;
      }
      ch[i].refuse_unknown();
    }
  }
  for (const auto& p : rig.plants)
    if (rig.safety.p_max_kPa > p.max_kPa)
      root.fail("safety.p_max_kPa", "at most the regulators' max_kPa (" + std::to_string(p.max_kPa) + ")");
  nlohmann::json backend_section;
  nlohmann::json load_cells;
  if (root.has("load_cells")) load_cells = root.raw("load_cells");
  if (rig.backend != "simulated") {
    if (!root.has(rig.backend)) root.fail(rig.backend, "a \"" + rig.backend + "\" section for that backend");
    backend_section = root.raw(rig.backend);
    if (root.has("channels")) backend_section["channels"] = root.raw("channels");
  }
  root.refuse_unknown();
  // A bad register map or DAQ section is refused at load, before anything is opened; the
  // parsed config is what make_backend uses.
  if (rig.backend == "modbus") rig.modbus = parse_modbus_config(rig, backend_section);
  if (rig.backend == "comedi") rig.comedi = parse_comedi_config(rig, backend_section);
  if (!load_cells.is_null()) rig.load_cells = parse_load_cell_config(rig, load_cells);
  return rig;
}

RigConfig load_rig_file(const std::filesystem::path& path) { return parse_rig(read_json_file(path), path.string()); }

RigConfig default_rig() {
  RigConfig rig;
  rig.source = "(built-in default rig)";
  rig.id = "sim-default";
  return rig;
}

}  // namespace palprig
