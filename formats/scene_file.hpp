#pragma once
// Scene files (JSON, versioned). A "map" scene is paper 002's measured stiffness map: a CSV or
// 16-bit PGM grid laid over a rectangle in mm, with its sampling rule, the policy outside it
// and, for experiments and the demo, the ground-truth outline of each tumor. A "function"
// scene describes the tissue by functions, with layers, inclusions and arteries
// (formats/function_scene_file.hpp); its tumors' outlines are measured from their shapes.
//
// Map orientation: column 0 / row 0 (the first CSV line, the top PGM row) is at x = 0, y = 0;
// y grows down the rows, as touchpad coordinates do.
#include <filesystem>

#include "formats/scene_description.hpp"
#include "models/scene.hpp"

namespace palprig {

SceneFile load_scene_file(const std::filesystem::path& path);
// A bare map file (.csv or .pgm) of the given size, as a MapScene.
StiffnessMap load_stiffness_map_file(const std::filesystem::path& path, double width_mm, double height_mm,
                                     double value_scale = 0.0);

}  // namespace palprig
