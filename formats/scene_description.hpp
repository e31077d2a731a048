#pragma once
// What a scene file describes once loaded: the scene the tick samples and the ground truth of
// its tumors. Both scene loaders (scene_file for maps, function_scene_file for functions)
// fill it; neither includes the other's header.
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

}  // namespace palprig
