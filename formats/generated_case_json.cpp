#include "formats/function_scene_file.hpp"
// The writing side of function scene files (declared in function_scene_file.hpp beside the
// reader): a generated rehearsal case as a scene file a trainer can open, edit and load again.

#include <string>

#include "io/checked_output.hpp"

namespace palprig {

nlohmann::json generated_case_json(const GeneratedCase& c) {
  using nlohmann::json;
  auto p3 = [](const Point3_mm& p) { return json::array({p.x_mm, p.y_mm, p.z_mm}); };
  json layers = json::array();
  for (const TissueLayer& l : c.layers)
    layers.push_back({{"name", l.name}, {"thickness_mm", l.thickness_mm}, {"stiffness_kPa", l.stiffness_kPa}});
  json inclusions = json::array();
  for (const GeneratedTumor& t : c.tumors) {
    json shape;
    switch (t.shape) {
      case GeneratedTumor::Shape::sphere:
        shape = {{"type", "sphere"}, {"centre_mm", p3(t.centre)}, {"radius_mm", t.radii_mm[0]}};
        break;
      case GeneratedTumor::Shape::ellipsoid:
        shape = {{"type", "ellipsoid"},
                 {"centre_mm", p3(t.centre)},
                 {"radii_mm", json::array({t.radii_mm[0], t.radii_mm[1], t.radii_mm[2]})},
                 {"yaw_deg", t.yaw_deg}};
        break;
      case GeneratedTumor::Shape::blobs: {
        json blobs = json::array();
        for (const Blob& b : t.lobes)
          blobs.push_back(
              {{"centre_mm", p3(b.centre)},
               {"k", b.k},
               {"inverse_scale_per_mm2",
                json::array({b.inverse_scale_per_mm2[0], b.inverse_scale_per_mm2[1], b.inverse_scale_per_mm2[2]})}});
        shape = {{"type", "blobs"}, {"threshold", t.threshold}, {"blobs", blobs}};
        break;
      }
    }
    inclusions.push_back({{"name", t.name}, {"kind", "tumor"}, {"stiffness_kPa", t.stiffness_kPa}, {"shape", shape}});
  }
  return {
      {"version", kSceneFileVersion},
      {"kind", "function"},
      {"name", std::string("case-") + to_string(c.difficulty) + "-" + std::to_string(c.seed)},
      {"description", "Generated rehearsal case (palprig scene generate): " + std::to_string(c.tumors.size()) +
                          " tumor(s), difficulty " + to_string(c.difficulty) +
                          ". The inclusions are the ground truth; do not show them to the trainee."},
      {"generator", {{"seed", c.seed}, {"difficulty", to_string(c.difficulty)}}},
      {"body",
       {{"centre_mm", json::array({c.body.centre.x_mm, c.body.centre.y_mm})},
        {"half_size_mm", json::array({c.body.half_width_mm, c.body.half_height_mm})},
        {"exponent", c.body.exponent}}},
      {"layers", layers},
      {"felt_range_kPa", {{"soft", c.felt.soft_kPa}, {"hard", c.felt.hard_kPa}}},
      {"inclusions", inclusions},
  };
}

void write_scene_json(const std::filesystem::path& path, const nlohmann::json& scene) {
  write_file_checked(path, scene.dump(2) + "\n");
}

}  // namespace palprig
