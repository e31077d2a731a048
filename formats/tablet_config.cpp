#include "formats/tablet_config.hpp"

#include <algorithm>

#include "formats/json_file.hpp"

namespace palprig {

double PressureCurve::force_N(double p) const noexcept {
  if (!(p > 0)) return points.front().second;
  if (p >= 1) return points.back().second;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (p <= points[i].first) {
      const auto& [p0, f0] = points[i - 1];
      const auto& [p1, f1] = points[i];
      return f0 + (p - p0) / (p1 - p0) * (f1 - f0);
    }
  }
  return points.back().second;
}

TabletConfig parse_tablet_config(const JsonObject& o) {
  TabletConfig t;
  t.device = o.string_or("device", t.device);
  if (t.device.empty()) o.fail("device", "\"auto\" or an event device path such as /dev/input/event5");
  if (o.has("origin_mm")) {
    const auto v = o.numbers("origin_mm", -10000, 10000);
    if (v.size() != 2) o.fail("origin_mm", "[x, y] in mm");
    t.origin_mm = {v[0], v[1]};
  }
  if (o.has("size_mm")) {
    const auto v = o.numbers("size_mm", 1, 10000);
    if (v.size() != 2) o.fail("size_mm", "[width, height] of the active area in mm");
    t.size_mm = {v[0], v[1]};
  }
  if (o.has("pressure_curve_N")) {
    const auto& raw = o.raw("pressure_curve_N");
    const std::string expected =
        "an array of [pressure 0..1, force N] points from pressure 0 to 1, pressure rising and force never falling";
    if (!raw.is_array() || raw.size() < 2) o.fail("pressure_curve_N", expected);
    t.pressure.points.clear();
    for (const auto& pt : raw) {
      if (!pt.is_array() || pt.size() != 2 || !pt[0].is_number() || !pt[1].is_number())
        o.fail("pressure_curve_N", expected);
      t.pressure.points.emplace_back(pt[0].get<double>(), pt[1].get<double>());
    }
    const auto& pts = t.pressure.points;
    bool ok =
        pts.front().first == 0.0 && pts.back().first == 1.0 && pts.front().second >= 0 && pts.back().second <= 100;
    for (std::size_t i = 1; i < pts.size(); ++i)
      ok = ok && pts[i].first > pts[i - 1].first && pts[i].second >= pts[i - 1].second;
    if (!ok) o.fail("pressure_curve_N", expected + " (forces 0..100 N)");
  }
  t.grab = o.boolean_or("grab", t.grab);
  t.reader_fifo_priority = static_cast<int>(o.integer_or("reader_fifo_priority", t.reader_fifo_priority, 0, 98));
  o.refuse_unknown();
  return t;
}

}  // namespace palprig
