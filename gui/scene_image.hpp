#pragma once
// The scene as a picture: felt stiffness 0..1 sampled on a grid over the scene's bounds (a
// stiffness map, or a function scene rendered at a pressing force and a time, so breathing
// organs move) and coloured soft-to-hard. Scene::sample is const and lock-free, so a worker
// thread may render while the loop samples the same scene.
#include <QColor>
#include <QImage>

#include "models/scene.hpp"

namespace palprig::gui {

// Colour for a felt stiffness 0 (soft, pale) .. 1 (hard, deep red).
QColor stiffness_colour(double stiffness) noexcept;
// Colour for a finger's pressure 0 .. p_max (blue, green, yellow, red).
QColor pressure_colour(double kPa, double p_max_kPa) noexcept;

// At most max_width x max_height pixels, the scene's aspect kept.
QImage render_scene_image(const Scene& scene, double force_N, double t_s, int max_width, int max_height);

}  // namespace palprig::gui
