#include "formats/scene_file.hpp"

#include <sstream>

#include "formats/function_scene_file.hpp"
#include "formats/json_file.hpp"
#include "io/regular_file.hpp"

namespace palprig {

StiffnessMap load_stiffness_map_file(const std::filesystem::path& path, double width_mm, double height_mm,
                                     double value_scale) {
  const std::string ext = path.extension().string();
  if (ext != ".csv" && ext != ".pgm") throw InputError(path.string(), "file name", "a .csv or .pgm stiffness map");
  std::istringstream in(read_regular_file(path, kMaxMapFileBytes, "a stiffness map"));
  if (ext == ".csv") return parse_stiffness_csv(in, path.string(), width_mm, height_mm, value_scale);
  if (ext == ".pgm") return parse_stiffness_pgm(in, path.string(), width_mm, height_mm);
  throw InputError(path.string(), "file name", "a .csv or .pgm stiffness map");
}

SceneFile load_scene_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  const nlohmann::json doc = read_json_file(path);
  JsonObject root(doc, file, "");
  root.require_version(kSceneFileVersion);
  SceneFile out;
  out.source = file;
  out.name = root.string_or("name", path.stem().string());
  const std::string kind = root.choice_or("kind", "map", {"map", "function"});
  (void)root.string_or("description", "");
  if (kind == "function") {  // a tissue block described by functions, with arteries
    load_function_scene(root, path, out);
    return out;
  }

  const JsonObject m = root.object("map");
  const std::string map_name = m.string("file");
  const double width_mm = m.number("width_mm", 1e-3, 1e5);
  const double height_mm = m.number("height_mm", 1e-3, 1e5);
  const double scale = m.number_or("value_scale", 0.0, 0.0, 1e9);
  const MapSampling sampling = m.choice_or("sampling", "nearest", {"nearest", "bilinear"}) == "nearest"
                                   ? MapSampling::nearest
                                   : MapSampling::bilinear;
  OutsidePolicy outside;
  if (m.has("outside")) {
    const auto& o = m.raw("outside");
    if (o.is_string() && o.get<std::string>() == "clamp") {
      outside.kind = OutsidePolicy::Kind::clamp;
    } else if (o.is_object()) {
      const JsonObject ob(o, file, m.path("outside"));
      outside.kind = OutsidePolicy::Kind::background;
      outside.background_stiffness = ob.number("background", 0, 1);
      ob.refuse_unknown();
    } else {
      m.fail("outside", "\"clamp\" or {\"background\": stiffness 0..1}, got " + json_excerpt(o));
    }
  }
  m.refuse_unknown();
  // A relative map path is relative to the scene file.
  std::filesystem::path map_path = map_name;
  if (map_path.is_relative()) map_path = path.parent_path() / map_path;
  StiffnessMap map = load_stiffness_map_file(map_path, width_mm, height_mm, scale);
  map.set_outside(outside);

  if (root.has("tumors")) {
    for (const JsonObject& t : root.objects("tumors")) {
      TumorTruth tt;
      tt.name = t.string("name");
      // A tumor is ground truth for scoring marks on the map: its centre lies on the map.
      tt.x_mm = t.number("x_mm", 0, width_mm);
      tt.y_mm = t.number("y_mm", 0, height_mm);
      tt.radius_mm = t.number("radius_mm", 1e-3, 1e4);
      if (t.has("depth_mm")) (void)t.number("depth_mm", 0, 1e4);  // documentation of the phantom
      if (t.has("stiffness_kPa")) (void)t.number("stiffness_kPa", 0, 1e7);
      t.refuse_unknown();
      out.tumors.push_back(tt);
    }
  }
  root.refuse_unknown();
  (void)kind;
  out.scene = std::make_unique<MapScene>(std::move(map), sampling);
  return out;
}

}  // namespace palprig
