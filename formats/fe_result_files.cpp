#include "formats/fe_result_files.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "formats/calibration_file.hpp"
#include "formats/json_file.hpp"
#include "io/checked_output.hpp"

namespace palprig {

namespace {

std::string result_number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

nlohmann::json inputs_json(const FeInputs& in) {
  nlohmann::json j = {{"fingertip", in.fingertip}, {"hash", in.hash}};
  if (!in.tissue.empty()) j["tissue"] = in.tissue;
  if (!in.actuator.empty()) j["actuator"] = in.actuator;
  return j;
}

FeInputs parse_inputs(const JsonObject& root) {
  FeInputs in;
  const JsonObject i = root.object("inputs");
  in.fingertip = i.string("fingertip");
  in.tissue = i.string_or("tissue", "");
  in.actuator = i.string_or("actuator", "");
  in.hash = i.string("hash");
  i.refuse_unknown();
  const JsonObject a = root.object("assumptions");
  in.plane = a.choice("plane", {"plane strain", "plane stress"});
  in.element_mm = a.number("element_mm", 0.01, 100);
  a.refuse_unknown();
  return in;
}

JsonObject open_root(const nlohmann::json& doc, const std::string& file, const std::string& kind) {
  JsonObject root(doc, file, "");
  root.require_version(kFeResultFileVersion);
  (void)root.choice("kind", {kind});
  (void)root.string_or("description", "");
  (void)root.string_or("generated_by", "");
  return root;
}

}  // namespace

std::string fe_result_kind(const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("kind") || !doc["kind"].is_string()) return "";
  const std::string k = doc["kind"].get<std::string>();
  return k == "stress_model" || k == "fe_stress_table" ? k : "";
}

nlohmann::json stress_model_json(const FeStressModelFile& m) {
  return {{"version", kFeResultFileVersion},
          {"kind", "stress_model"},
          {"generated_by", "palprig fe stress-model"},
          {"inputs", inputs_json(m.inputs)},
          {"assumptions", {{"plane", m.inputs.plane}, {"element_mm", m.inputs.element_mm}}},
          {"tissue",
           {{"indentation_mm", m.indentation_mm},
            {"soft_stress_kPa", m.soft_stress_kPa},
            {"hard_stress_kPa", m.hard_stress_kPa}}},
          {"actuator",
           {{"press_mm", m.press_mm},
            {"loading", m.loading},
            {"uninflated", m.uninflated},
            {"slope", m.actuator.slope},
            {"intercept_kPa", m.actuator.intercept_kPa},
            {"r_squared", m.r_squared},
            {"pressures_kPa", m.pressures_kPa},
            {"stresses_kPa", m.stresses_kPa}}},
          {"nodule_pressure_kPa", m.nodule_pressure_kPa}};
}

FeStressModelFile parse_stress_model(const nlohmann::json& doc, const std::string& file) {
  const JsonObject root = open_root(doc, file, "stress_model");
  FeStressModelFile m;
  m.file = file;
  m.inputs = parse_inputs(root);
  const JsonObject t = root.object("tissue");
  m.indentation_mm = t.number("indentation_mm", 0.01, 100);
  m.soft_stress_kPa = t.number("soft_stress_kPa", 1e-6, 1000);
  m.hard_stress_kPa = t.number("hard_stress_kPa", 1e-6, 1000);
  if (!(m.hard_stress_kPa > m.soft_stress_kPa))
    t.fail("hard_stress_kPa",
           "a nodule stress above the soft-tissue stress (" + result_number_text(m.soft_stress_kPa) + " kPa)");
  t.refuse_unknown();
  const JsonObject a = root.object("actuator");
  m.press_mm = a.number("press_mm", 0.01, 100);
  m.loading = a.choice_or("loading", "press-first", {"press-first", "together"});
  m.uninflated = a.choice_or("uninflated", "fitted", {"fitted", "soft-tissue"});
  m.actuator.slope = a.number("slope", 1e-9, kMaxActuatorSlope);
  // The calibration file's rule: an intercept at or above the hard stress makes every target 0 kPa.
  m.actuator.intercept_kPa = a.number("intercept_kPa", kMinActuatorIntercept_kPa, 1000);
  if (m.uninflated == "soft-tissue" &&
      !(std::abs(m.actuator.intercept_kPa - m.soft_stress_kPa) <= 1e-9 * std::max(1.0, m.soft_stress_kPa)))
    a.fail("intercept_kPa", "the soft-tissue stress (" + result_number_text(m.soft_stress_kPa) +
                                " kPa), as \"uninflated\": \"soft-tissue\" says");
  if (!(m.actuator.intercept_kPa < m.hard_stress_kPa))
    a.fail("intercept_kPa", "the uninflated actuator's stress below the nodule stress (" +
                                result_number_text(m.hard_stress_kPa) +
                                " kPa): otherwise no air pressure renders a nodule");
  m.r_squared = a.number("r_squared", -1e9, 1);
  m.pressures_kPa = a.numbers("pressures_kPa", 0, 1000);
  m.stresses_kPa = a.numbers("stresses_kPa", -1000, 1000);
  if (m.pressures_kPa.size() != m.stresses_kPa.size())
    a.fail("stresses_kPa", "one stress per pressure (" + std::to_string(m.pressures_kPa.size()) + ")");
  a.refuse_unknown();
  m.nodule_pressure_kPa = root.number("nodule_pressure_kPa", -1000, 1000);
  root.refuse_unknown();
  return m;
}

FeStressModelFile load_stress_model_file(const std::filesystem::path& path) {
  return parse_stress_model(read_json_file(path), path.string());
}

void write_stress_model_file(const std::filesystem::path& path, const FeStressModelFile& m) {
  const nlohmann::json doc = stress_model_json(m);
  (void)parse_stress_model(doc, path.string());  // refused here, naming the file, before anything is written
  CheckedOutputFile out(path);
  out.write(doc.dump(2) + "\n");
  out.commit([](const std::filesystem::path& written) { (void)load_stress_model_file(written); });
}

nlohmann::json fe_table_json(const FeTableFile& t) {
  const FeTableAxes& ax = t.table->axes();
  return {{"version", kFeResultFileVersion},
          {"kind", "fe_stress_table"},
          {"generated_by", "palprig fe table"},
          {"inputs", inputs_json(t.inputs)},
          {"assumptions", {{"plane", t.inputs.plane}, {"element_mm", t.inputs.element_mm}}},
          {"axes",
           {{"indentation_mm", ax.indentation_mm},
            {"cover_mm", ax.cover_mm},
            {"diameter_mm", ax.diameter_mm},
            {"contrast", ax.contrast},
            {"offset_mm", ax.offset_mm}}},
          {"healthy_kPa", t.table->healthy()},
          {"peak_kPa", t.table->peaks_kPa()},
          {"build", {{"solves", t.solves}, {"wall_s", t.wall_s}, {"workers", t.workers}}}};
}

FeTableFile parse_fe_table(const nlohmann::json& doc, const std::string& file) {
  const JsonObject root = open_root(doc, file, "fe_stress_table");
  FeTableFile t;
  t.file = file;
  t.inputs = parse_inputs(root);
  const JsonObject ax = root.object("axes");
  FeTableAxes axes;
  axes.indentation_mm = ax.numbers("indentation_mm", 1e-3, 100);
  axes.cover_mm = ax.numbers("cover_mm", 0, 1000);
  axes.diameter_mm = ax.numbers("diameter_mm", 1e-3, 1000);
  axes.contrast = ax.numbers("contrast", 1.000001, 1e6);
  axes.offset_mm = ax.numbers("offset_mm", 0, 1000);
  ax.refuse_unknown();
  // The grid is bounded before its values are read: 10^6 values is a table far beyond any build.
  for (const auto* a : {&axes.indentation_mm, &axes.cover_mm, &axes.diameter_mm, &axes.contrast, &axes.offset_mm})
    if (a->empty() || a->size() > 64) ax.fail("indentation_mm", "axes of 1..64 points each");
  std::vector<double> healthy = root.numbers("healthy_kPa", 0, 1e5);
  std::vector<double> peak = root.numbers("peak_kPa", 0, 1e5);
  if (peak.size() != axes.values())
    root.fail("peak_kPa",
              "one value per grid point (" + std::to_string(axes.values()) + "), got " + std::to_string(peak.size()));
  if (healthy.size() != axes.indentation_mm.size())
    root.fail("healthy_kPa", "one value per indentation depth (" + std::to_string(axes.indentation_mm.size()) + ")");
  try {
    t.table = std::make_shared<const FeStressTable>(axes, std::move(peak), std::move(healthy));
  } catch (const std::invalid_argument& e) {
    root.fail("axes", std::string("a table grid: ") + e.what());
  }
  if (root.has("build")) {
    const JsonObject b = root.object("build");
    t.solves = std::size_t(b.integer_or("solves", 0, 0, 1000000));
    t.wall_s = b.number_or("wall_s", 0, 0, 1e9);
    t.workers = int(b.integer_or("workers", 0, 0, 1024));
    b.refuse_unknown();
  }
  root.refuse_unknown();
  return t;
}

FeTableFile load_fe_table_file(const std::filesystem::path& path) {
  return parse_fe_table(read_json_file(path), path.string());
}

void write_fe_table_file(const std::filesystem::path& path, const FeTableFile& t) {
  const nlohmann::json doc = fe_table_json(t);
  (void)parse_fe_table(doc, path.string());
  CheckedOutputFile out(path);
  out.write(doc.dump(1) + "\n");
  out.commit([](const std::filesystem::path& written) { (void)load_fe_table_file(written); });
}

}  // namespace palprig
