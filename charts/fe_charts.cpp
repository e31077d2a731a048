#include "charts/fe_charts.hpp"

#include <QtCore/QBuffer>
#include <QtCore/QByteArray>
#include <QtGui/QImage>
#include <QtGui/QLinearGradient>
#include <QtGui/QPainter>
#include <QtGui/QPainterPath>
#include <QtSvg/QSvgGenerator>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "charts/chart_png.hpp"
#include "charts/chart_svg.hpp"
#include "io/checked_output.hpp"

namespace palprig::charts {

namespace {

using mechanics::ContactRun;
using mechanics::MeshNode;

std::vector<std::filesystem::path> write_both(const Chart& chart, const std::filesystem::path& stem) {
  std::filesystem::path png = stem, svg = stem;
  png += ".png";
  svg += ".svg";
  write_chart_png(chart, png);
  write_chart_svg(chart, svg);
  return {png, svg};
}

// Blue -> cyan -> green -> yellow -> red, as ABAQUS's default contour.
QColor rainbow(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const double h = (1 - t) * 240.0;  // hue 240 (blue) to 0 (red)
  return QColor::fromHsvF(h / 360.0, 0.85, 0.95);
}

struct View {
  double x0, y0, x1, y1;  // mm
  QRectF area;            // pixels
  QPointF map(const MeshNode& n) const {
    const double sx = area.width() / (x1 - x0), sy = area.height() / (y1 - y0);
    const double s = std::min(sx, sy);
    const double ox = area.left() + (area.width() - s * (x1 - x0)) / 2;
    const double oy = area.top() + (area.height() - s * (y1 - y0)) / 2;
    return {ox + s * (n.x_mm - x0), oy + s * (y1 - n.y_mm)};
  }
};

constexpr int kWidth = 1000, kHeight = 760;
constexpr int kOutline[8] = {0, 1, 2, 5, 8, 7, 6, 3};

void paint_mesh(QPainter& p, const std::string& title, const ContactRun& run, double max_kPa) {
  const auto& nodes = run.last.nodes;
  const auto& vm = run.last.von_mises_kPa;
  p.setRenderHint(QPainter::Antialiasing, true);
  p.fillRect(QRect(0, 0, kWidth, kHeight), Qt::white);
  // The view: the fingertip and 12 mm around it (down and to the sides), 1 mm above it.
  double fx0 = 1e300, fx1 = -1e300, fy0 = 1e300, fy1 = -1e300;
  for (const auto& e : run.mesh.elements)
    if (e.body == 0)
      for (auto id : e.nodes) {
        fx0 = std::min(fx0, nodes[id].x_mm);
        fx1 = std::max(fx1, nodes[id].x_mm);
        fy0 = std::min(fy0, nodes[id].y_mm);
        fy1 = std::max(fy1, nodes[id].y_mm);
      }
  View v{fx0 - 12, fy0 - 12, fx1 + 12, fy1 + 1, QRectF(20, 60, kWidth - 170, kHeight - 90)};
  auto visible = [&](const mechanics::QuadElement& e) {
    for (auto id : e.nodes)
      if (nodes[id].x_mm >= v.x0 && nodes[id].x_mm <= v.x1 && nodes[id].y_mm >= v.y0 && nodes[id].y_mm <= v.y1)
        return true;
    return false;
  };
  if (!(max_kPa > 0)) {
    std::vector<double> shown;
    for (std::size_t i = 0; i < run.mesh.elements.size(); ++i)
      if (visible(run.mesh.elements[i]) && std::isfinite(vm[i])) shown.push_back(vm[i]);
    std::sort(shown.begin(), shown.end());
    max_kPa = shown.empty() ? 1.0 : shown[std::size_t(0.99 * double(shown.size() - 1))];
    if (!(max_kPa > 0)) max_kPa = 1.0;
  }
  p.save();
  p.setClipRect(v.area);
  QPen edge(QColor(40, 40, 40, 140));
  edge.setWidthF(0.5);
  p.setPen(edge);
  for (std::size_t i = 0; i < run.mesh.elements.size(); ++i) {
    const auto& e = run.mesh.elements[i];
    if (!visible(e)) continue;
    QPolygonF poly;
    for (int k : kOutline) poly << v.map(nodes[e.nodes[std::size_t(k)]]);
    p.setBrush(std::isfinite(vm[i]) ? rainbow(vm[i] / max_kPa) : QColor(Qt::magenta));
    p.drawPolygon(poly);
  }
  // The bone (not meshed: the press is applied to its outline), in grey.
  if (run.mesh.has_boundary("bone")) {
    std::vector<std::uint32_t> ring;
    for (const auto& s : run.mesh.boundary("bone"))
      for (auto id : run.mesh.side_nodes(s)) ring.push_back(id);
    double cx = 0, cy = 0;
    for (auto id : ring) {
      cx += nodes[id].x_mm / double(ring.size());
      cy += nodes[id].y_mm / double(ring.size());
    }
    std::sort(ring.begin(), ring.end(), [&](auto a, auto b) {
      return std::atan2(nodes[a].y_mm - cy, nodes[a].x_mm - cx) < std::atan2(nodes[b].y_mm - cy, nodes[b].x_mm - cx);
    });
    QPolygonF bone;
    for (auto id : ring) bone << v.map(nodes[id]);
    p.setBrush(QColor(200, 200, 200));
    p.setPen(QPen(QColor(90, 90, 90), 1.0));
    p.drawPolygon(bone);
  }
  p.restore();
  // Title and colour bar.
  QFont font = p.font();
  font.setPixelSize(18);
  p.setFont(font);
  p.setPen(Qt::black);
  p.drawText(QRectF(20, 10, kWidth - 40, 40), Qt::AlignLeft | Qt::AlignVCenter, QString::fromStdString(title));
  const QRectF bar(kWidth - 120, 90, 24, kHeight - 180);
  QLinearGradient g(bar.bottomLeft(), bar.topLeft());
  for (int k = 0; k <= 10; ++k) g.setColorAt(k / 10.0, rainbow(k / 10.0));
  p.fillRect(bar, g);
  p.setPen(QPen(Qt::black, 1));
  p.setBrush(Qt::NoBrush);
  p.drawRect(bar);
  font.setPixelSize(13);
  p.setFont(font);
  for (int k = 0; k <= 5; ++k) {
    const double value = max_kPa * k / 5;
    const double y = bar.bottom() - bar.height() * k / 5;
    char label[32];
    std::snprintf(label, sizeof label, k == 5 ? ">= %.3g" : "%.3g", value);
    p.drawLine(QPointF(bar.right(), y), QPointF(bar.right() + 5, y));
    p.drawText(QRectF(bar.right() + 8, y - 9, 80, 18), Qt::AlignLeft | Qt::AlignVCenter, label);
  }
  p.drawText(QRectF(bar.left() - 30, bar.top() - 30, 140, 20), Qt::AlignLeft, "von Mises, kPa");
}

}  // namespace

std::vector<std::filesystem::path> write_contact_stress_figure(const std::filesystem::path& stem,
                                                               const std::string& title,
                                                               const std::vector<ProfileCurve>& curves) {
  Chart c;
  c.title = title;
  c.x_label = "position across the fingertip, deformed (mm)";
  c.y_label = "contact stress, 1 mm average (kPa)";
  for (const ProfileCurve& curve : curves) {
    if (!curve.step) continue;
    ChartSeries s;
    s.label = curve.label;
    for (const auto& n : curve.step->profile) {
      const double p =
          mechanics::averaged_stress_kPa(curve.step->profile, n.s_mm, mechanics::kStressAveragingLength_mm / 2);
      if (p <= 1e-3 * curve.step->peak_kPa) continue;  // off the contact
      s.x.push_back(n.x_mm);
      s.y.push_back(p);
    }
    // The lower half of the outline is one curve in x; sort to draw it left to right.
    std::vector<std::size_t> order(s.x.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return s.x[a] < s.x[b]; });
    ChartSeries sorted = s;
    for (std::size_t i = 0; i < order.size(); ++i) {
      sorted.x[i] = s.x[order[i]];
      sorted.y[i] = s.y[order[i]];
    }
    if (!sorted.x.empty()) c.series.push_back(sorted);
  }
  c.y_min = 0;
  return write_both(c, stem);
}

std::vector<std::filesystem::path> write_peak_figure(const std::filesystem::path& stem, const std::string& title,
                                                     const std::string& x_label,
                                                     const std::vector<PeakSeries>& series) {
  Chart c;
  c.title = title;
  c.x_label = x_label;
  c.y_label = "peak contact stress (kPa)";
  for (const PeakSeries& p : series) {
    ChartSeries points;
    points.label = p.label;
    points.style = p.line ? ChartSeries::Style::points : ChartSeries::Style::line;
    points.x = p.load;
    points.y = p.peak_kPa;
    c.series.push_back(points);
    if (p.line && !p.load.empty()) {
      ChartSeries fit;
      char label[160];
      std::snprintf(label, sizeof label, "fit: %.4f p + %.3f, R^2 %.4f", p.line->slope, p.line->intercept_kPa,
                    p.line->r_squared);
      fit.label = label;
      const auto [lo, hi] = std::minmax_element(p.load.begin(), p.load.end());
      fit.x = {*lo, *hi};
      fit.y = {p.line->slope * *lo + p.line->intercept_kPa, p.line->slope * *hi + p.line->intercept_kPa};
      fit.width_px = 1.5;
      c.series.push_back(fit);
    }
  }
  c.y_min = 0;
  return write_both(c, stem);
}

std::vector<std::filesystem::path> write_deformed_mesh_figure(const std::filesystem::path& stem,
                                                              const std::string& title, const ContactRun& run,
                                                              double max_kPa) {
  if (run.last.nodes.size() != run.mesh.nodes.size() || run.last.von_mises_kPa.size() != run.mesh.elements.size())
    throw std::invalid_argument("the run has no deformed mesh to draw");
  ensure_chart_application();
  std::filesystem::path png = stem, svg = stem;
  png += ".png";
  svg += ".svg";
  {
    QImage image(kWidth, kHeight, QImage::Format_ARGB32);
    QPainter p(&image);
    paint_mesh(p, title, run, max_kPa);
    p.end();
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    if (!image.save(&buffer, "PNG")) throw OutputError(png, "the PNG could not be encoded");
    write_file_checked(png, std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
  }
  {
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    {
      QSvgGenerator generator;
      generator.setOutputDevice(&buffer);
      generator.setSize(QSize(kWidth, kHeight));
      generator.setViewBox(QRect(0, 0, kWidth, kHeight));
      generator.setTitle(QString::fromStdString(title));
      QPainter p;
      if (!p.begin(&generator)) throw OutputError(svg, "the SVG could not be drawn");
      paint_mesh(p, title, run, max_kPa);
      p.end();
    }
    write_file_checked(svg, std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
  }
  return {png, svg};
}

}  // namespace palprig::charts
