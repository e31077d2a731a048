#pragma once
// Scene files (JSON, versioned). A "map" scene is paper 002's measured stiffness map: a CSV or
// 16-bit PGM grid laid over a rectangle in mm, with its sampling rule, the policy outside it
// and, for experiments and the demo, the ground-truth outline of each tumor. A "function"
// scene describes the tissue by functions, with layers, inclusions and arteries
// (controller/function_scene_file.hpp); its tumors' outlines are measured from their shapes.
//
// Map orientation: column 0 / row 0 (the first CSV line, the top PGM row) is at x = 0, y = 0;
// y grows down the rows, as touchpad coordinates do.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "models/scene.hpp"

namespace palprig {

inline constexpr int kSceneFileVersion = 1;

struct TumorTruth {
  std::string name;
  double x_mm = 0, y_mm = 0, radius_mm = 0;  // circular outline on the surface
};

struct SceneFile {
  std::string source;
  std::string name;
  std::unique_ptr<Scene> scene;
  std::vector<TumorTruth> tumors;
};

SceneFile load_scene_file(const std::filesystem::path& path);
// A bare map file (.csv or .pgm) of the given size, as a MapScene.
StiffnessMap load_stiffness_map_file(const std::filesystem::path& path, double width_mm, double height_mm,
                                     double value_scale = 0.0);

}  // namespace palprig
