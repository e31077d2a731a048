#include "formats/fe_body_files.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace palprig {

namespace {

std::string body_number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// The root of one of the three files: version and kind checked, name and description read.
JsonObject open_root(const nlohmann::json& doc, const std::string& file, const std::string& kind, std::string& name) {
  JsonObject root(doc, file, "");
  root.require_version(kFeBodyFileVersion);
  (void)root.choice("kind", {kind});
  name = root.string_or("name", "");
  (void)root.string_or("description", "");
  return root;
}

MaterialLaw material_or(const JsonObject& parent, const std::string& key, const MaterialLaw& fallback) {
  if (!parent.has(key)) return fallback;
  return parse_material(parent.object(key));
}

}  // namespace

MaterialLaw parse_material(const JsonObject& o) {
  const std::string law = o.choice("law", {"ogden", "arruda_boyce", "linear_elastic"});
  MaterialLaw m;
  if (law == "ogden") {
    m = MaterialLaw::ogden(o.number("mu_kPa", 1e-6, 1e7), o.number("alpha", -50, 50));
    if (std::abs(m.alpha) < 0.1) o.fail("alpha", "an Ogden exponent of magnitude 0.1..50 (0 has no stress)");
  } else if (law == "arruda_boyce") {
    m = MaterialLaw::arruda_boyce(o.number("mu_kPa", 1e-6, 1e7), o.number("locking_stretch", 1.001, 100));
  } else {
    const int given = int(o.has("youngs_kPa")) + int(o.has("shore_a")) + int(o.has("shore_d"));
    if (given != 1) o.fail("youngs_kPa", "exactly one of youngs_kPa, shore_a (20..80) or shore_d (30..85)");
    double e = 0;
    if (o.has("youngs_kPa")) e = o.number("youngs_kPa", 1e-6, 1e9);
    if (o.has("shore_a")) e = youngs_from_shore_a_kPa(o.number("shore_a", 20, 80));  // paper 002 eq. 3-4
    if (o.has("shore_d")) e = youngs_from_shore_d_kPa(o.number("shore_d", 30, 85));
    m = MaterialLaw::linear_elastic(e, o.number("poisson", 0, 0.499));
  }
  m.density_kg_m3 = o.number_or("density_kg_m3", 0, 0, 1e5);
  o.refuse_unknown();
  return m;
}

std::string fe_body_kind(const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("kind") || !doc["kind"].is_string()) return "";
  const std::string k = doc["kind"].get<std::string>();
  return k == "fingertip" || k == "tissue" || k == "actuator" ? k : "";
}

FingertipBody parse_fingertip(const nlohmann::json& doc, const std::string& file) {
  std::string name;
  const JsonObject root = open_root(doc, file, "fingertip", name);
  FingertipBody f;
  const JsonObject outline = root.object("outline");
  f.width_mm = outline.number("width_mm", 4, 40);
  f.height_mm = outline.number("height_mm", 4, 40);
  f.outline_exponent = outline.number_or("exponent", 2.0, 1.5, 10);
  outline.refuse_unknown();
  const double least = std::min(f.width_mm, f.height_mm);
  f.skin_thickness_mm = root.number("skin_thickness_mm", 0.1, least / 4);
  const JsonObject bone = root.object("bone");
  f.bone_width_mm = bone.number("width_mm", 0.5, f.width_mm);
  f.bone_height_mm = bone.number("height_mm", 0.5, f.height_mm);
  f.bone_centre_height_mm = bone.number("centre_height_mm", 0, f.height_mm);
  bone.refuse_unknown();
  // The bone must lie inside the tissue with room for at least a thin layer (0.5 mm) between it
  // and the skin: checked on its outline against the outline shrunk by skin and margin.
  const double a = f.width_mm / 2 - f.skin_thickness_mm - 0.5, b = f.height_mm / 2 - f.skin_thickness_mm - 0.5;
  for (int k = 0; k < 72; ++k) {
    const double t = 2 * std::numbers::pi * k / 72;
    const double x = f.bone_width_mm / 2 * std::cos(t),
                 y = f.bone_centre_height_mm + f.bone_height_mm / 2 * std::sin(t);
    const double level =
        std::pow(std::abs(x) / a, f.outline_exponent) + std::pow(std::abs(y - f.height_mm / 2) / b, f.outline_exponent);
    if (!(a > 0 && b > 0 && level < 1))
      bone.fail("centre_height_mm", "a bone inside the tissue, at least 0.5 mm from the skin (outline " +
                                        body_number_text(f.width_mm) + " x " + body_number_text(f.height_mm) +
                                        " mm, skin " + body_number_text(f.skin_thickness_mm) + " mm)");
  }
  if (root.has("nail")) {
    const JsonObject nail = root.object("nail");
    f.nail_width_mm = nail.number("width_mm", 0, f.width_mm);
    nail.refuse_unknown();
  } else {
    f.nail_width_mm = 0;
  }
  if (root.has("materials")) {
    const JsonObject m = root.object("materials");
    f.skin = material_or(m, "skin", f.skin);
    f.tissue = material_or(m, "tissue", f.tissue);
    f.nail = material_or(m, "nail", f.nail);
    f.bone = material_or(m, "bone", f.bone);
    m.refuse_unknown();
  }
  root.refuse_unknown();
  return f;
}

TissueBlock parse_tissue(const nlohmann::json& doc, const std::string& file) {
  TissueBlock t;
  const JsonObject root = open_root(doc, file, "tissue", t.name);
  const JsonObject block = root.object("block");
  t.width_mm = block.number("width_mm", 5, 500);
  t.height_mm = block.number("height_mm", 5, 500);
  t.sides = block.choice_or("sides", "free", {"free", "rollers"}) == "rollers" ? BlockSides::rollers : BlockSides::free;
  block.refuse_unknown();
  t.tissue = material_or(root, "material", t.tissue);
  if (root.has("inclusions")) {
    const auto list = root.objects("inclusions");
    if (list.size() > 8) root.fail("inclusions", "at most 8 inclusions, got " + std::to_string(list.size()));
    for (std::size_t i = 0; i < list.size(); ++i) {
      const JsonObject& o = list[i];
      BlockInclusion inc;
      inc.name = o.string_or("name", "inclusion " + std::to_string(i + 1));
      inc.diameter_mm = o.number("diameter_mm", 0.5, t.width_mm);
      const double r = inc.diameter_mm / 2;
      inc.x_mm = o.number_or("x_mm", 0, -t.width_mm / 2, t.width_mm / 2);
      if (std::abs(inc.x_mm) + r > t.width_mm / 2 - 0.5)
        o.fail("x_mm", "an inclusion at least 0.5 mm inside the block's sides (half width " +
                           body_number_text(t.width_mm / 2) + " mm, radius " + body_number_text(r) + " mm)");
      inc.centre_depth_mm = o.number("centre_depth_mm", 0, t.height_mm);
      if (inc.centre_depth_mm - r < 0.5)
        o.fail("centre_depth_mm", "a centre at least 0.5 mm deeper than the radius (" + body_number_text(r) +
                                      " mm): the inclusion must stay under the surface");
      if (inc.centre_depth_mm + r > t.height_mm - 0.5)
        o.fail("centre_depth_mm",
               "an inclusion at least 0.5 mm above the block's bottom (" + body_number_text(t.height_mm) + " mm)");
      inc.law = material_or(o, "material", inc.law);
      o.refuse_unknown();
      for (const BlockInclusion& other : t.inclusions) {
        const double gap =
            std::hypot(other.x_mm - inc.x_mm, other.centre_depth_mm - inc.centre_depth_mm) - r - other.diameter_mm / 2;
        if (gap < 0.5)
          o.fail("centre_depth_mm",
                 "inclusions at least 0.5 mm apart (" + other.name + " is " + body_number_text(gap) + " mm away)");
      }
      t.inclusions.push_back(inc);
    }
  }
  root.refuse_unknown();
  return t;
}

ActuatorBody parse_actuator(const nlohmann::json& doc, const std::string& file) {
  ActuatorBody a;
  const JsonObject root = open_root(doc, file, "actuator", a.name);
  a.width_mm = root.number("width_mm", 4, 200);
  const JsonObject chamber = root.object("chamber");
  a.chamber_width_mm = chamber.number("width_mm", 0.5, a.width_mm - 2);
  a.chamber_depth_mm = chamber.number("depth_mm", 0.05, 50);
  chamber.refuse_unknown();
  const JsonObject membrane = root.object("membrane");
  a.membrane_thickness_mm = membrane.number("thickness_mm", 0.02, 5);
  a.membrane = material_or(membrane, "material", a.membrane);
  a.membrane_slides = membrane.choice_or("on_substrate", "bonded", {"bonded", "sliding"}) == "sliding";
  membrane.refuse_unknown();
  const JsonObject layer = root.object("layer");
  a.layer_thickness_mm = layer.number("thickness_mm", 0.2, 50);
  a.layer = material_or(layer, "material", a.layer);
  layer.refuse_unknown();
  root.refuse_unknown();
  return a;
}

FingertipBody load_fingertip_file(const std::filesystem::path& path) {
  return parse_fingertip(read_json_file(path), path.string());
}
TissueBlock load_tissue_file(const std::filesystem::path& path) {
  TissueBlock t = parse_tissue(read_json_file(path), path.string());
  if (t.name.empty()) t.name = path.stem().string();
  return t;
}
ActuatorBody load_actuator_file(const std::filesystem::path& path) {
  ActuatorBody a = parse_actuator(read_json_file(path), path.string());
  if (a.name.empty()) a.name = path.stem().string();
  return a;
}

}  // namespace palprig
