#include "gui/scene_image.hpp"

#include <algorithm>
#include <cmath>

namespace palprig::gui {

namespace {

QColor blend(const QColor& a, const QColor& b, double f) {
  f = std::clamp(f, 0.0, 1.0);
  return QColor::fromRgbF(float(a.redF() + (b.redF() - a.redF()) * f),
                          float(a.greenF() + (b.greenF() - a.greenF()) * f),
                          float(a.blueF() + (b.blueF() - a.blueF()) * f));
}

}  // namespace

QColor stiffness_colour(double s) noexcept {
  if (!std::isfinite(s)) return QColor(40, 40, 40);
  static const QColor stops[] = {QColor(252, 236, 226), QColor(240, 170, 150), QColor(205, 85, 75),
                                 QColor(120, 20, 30)};
  const double x = std::clamp(s, 0.0, 1.0) * 3.0;
  const int i = std::min(int(x), 2);
  return blend(stops[i], stops[i + 1], x - i);
}

QColor pressure_colour(double kPa, double p_max_kPa) noexcept {
  static const QColor stops[] = {QColor(60, 110, 220), QColor(40, 180, 90), QColor(240, 200, 40), QColor(220, 40, 30)};
  const double f = p_max_kPa > 0 && std::isfinite(kPa) ? std::clamp(kPa / p_max_kPa, 0.0, 1.0) : 0.0;
  const double x = f * 3.0;
  const int i = std::min(int(x), 2);
  return blend(stops[i], stops[i + 1], x - i);
}

QImage render_scene_image(const Scene& scene, double force_N, double t_s, int max_width, int max_height) {
  const SceneBounds b = scene.bounds();
  const double w_mm = b.x1_mm - b.x0_mm, h_mm = b.y1_mm - b.y0_mm;
  if (!(w_mm > 0) || !(h_mm > 0) || max_width < 1 || max_height < 1) return QImage();
  const double px_per_mm = std::min(max_width / w_mm, max_height / h_mm);
  const int w = std::max(1, int(std::lround(w_mm * px_per_mm))), h = std::max(1, int(std::lround(h_mm * px_per_mm)));
  QImage img(w, h, QImage::Format_RGB32);
  for (int y = 0; y < h; ++y) {
    auto* line = reinterpret_cast<QRgb*>(img.scanLine(y));
    const double y_mm = b.y0_mm + (y + 0.5) / px_per_mm;
    for (int x = 0; x < w; ++x) {
      const double x_mm = b.x0_mm + (x + 0.5) / px_per_mm;
      line[x] = stiffness_colour(scene.sample({x_mm, y_mm}, force_N, t_s).stiffness).rgb();
    }
  }
  return img;
}

}  // namespace palprig::gui
