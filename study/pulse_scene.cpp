#include "study/pulse_scene.hpp"

#include <string>

#include "formats/function_scene_file.hpp"
#include "formats/json_file.hpp"
#include "study/random_source.hpp"

namespace palprig {

SceneFile generated_pulse_scene(std::uint64_t seed, CaseDifficulty difficulty) {
  const GeneratedCase c = generate_case(seed, difficulty);
  nlohmann::json doc = generated_case_json(c);
  RandomSource random(seed ^ 0xA5A5A5A5DEADBEEFULL);
  const double cx = c.body.centre.x_mm, cy = c.body.centre.y_mm;
  const double hx = c.body.half_width_mm, hy = c.body.half_height_mm;
  const double x0 = cx + (random.uniform() - 0.5) * hx;  // enters within the middle half
  const double x1 = cx + (random.uniform() - 0.5) * hx;
  const double xm = 0.5 * (x0 + x1) + (random.uniform() - 0.5) * 0.4 * hx;
  const double depth = difficulty == CaseDifficulty::easy ? 6.0 : difficulty == CaseDifficulty::medium ? 10.0 : 14.0;
  doc["arteries"] = nlohmann::json::array({{{"name", "artery"},
                                            {"path_mm", {{x0, cy - 0.85 * hy}, {xm, cy}, {x1, cy + 0.85 * hy}}},
                                            {"depth_mm", depth},
                                            {"radius_mm", 3.0},
                                            {"amplitude_kPa", 8.0},
                                            {"rate_bpm", 60.0 + 40.0 * random.uniform()},
                                            {"waveform", {{"shape", "rectangular"}, {"duty", 0.2}}},
                                            {"force_window_N", {1.0, 4.0}}}});
  const std::string source = "generated pulse case (seed " + std::to_string(seed) + ", " + to_string(difficulty) + ")";
  const JsonObject root(doc, source, "");
  root.require_version(1);
  SceneFile out;
  out.source = source;
  out.name = root.string_or("name", "generated");
  (void)root.choice_or("kind", "function", {"function"});
  (void)root.string_or("description", "");
  load_function_scene(root, std::filesystem::path("."), out);
  return out;
}

}  // namespace palprig
