#include "charts/chart_png.hpp"

#include <QtCore/QBuffer>
#include <QtCore/QByteArray>
#include <QtGui/QFont>
#include <QtGui/QFontMetrics>
#include <QtGui/QGuiApplication>
#include <QtGui/QImage>
#include <QtGui/QPainter>
#include <QtGui/QPainterPath>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/error.hpp"
#include "io/checked_output.hpp"

namespace palprig::charts {

namespace {

// Text needs Qt's font database, which needs a QGuiApplication; the offscreen platform needs
// no display. A GUI that already runs keeps its own application.
QtMessageHandler previous_handler = nullptr;

// Without a desktop session Qt warns that XDG_RUNTIME_DIR is unset; a command line drawing a
// chart has no use for it, so that one line is dropped and everything else passes through.
void quiet_runtime_dir_warning(QtMsgType type, const QMessageLogContext& context, const QString& message) {
  if (type == QtWarningMsg && message.startsWith(QLatin1String("QStandardPaths: XDG_RUNTIME_DIR not set"))) return;
  if (previous_handler)
    previous_handler(type, context, message);
  else
    fprintf(stderr, "%s\n", qPrintable(message));
}

void ensure_application() {
  if (QCoreApplication::instance()) return;
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  previous_handler = qInstallMessageHandler(quiet_runtime_dir_warning);
  static int argc = 1;
  static char name[] = "palprig";
  static char* argv[] = {name, nullptr};
  static QGuiApplication* app = new QGuiApplication(argc, argv);  // lives as long as the process
  (void)app;
}

constexpr unsigned kPalette[] = {0x1f77b4, 0xd62728, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b, 0xe377c2, 0x7f7f7f};

QColor colour(unsigned rgb) { return QColor(int((rgb >> 16) & 0xff), int((rgb >> 8) & 0xff), int(rgb & 0xff)); }

// A tick step of 1, 2 or 5 times a power of ten giving about `target` ticks.
double nice_step(double span, int target) {
  const double raw = span / std::max(target, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * p) return m * p;
  return 10 * p;
}

QString number_text(double v, double step) {
  const int decimals = std::clamp(int(-std::floor(std::log10(step) + 1e-9)), 0, 6);
  return QString::number(std::abs(v) < step * 1e-9 ? 0.0 : v, 'f', decimals);
}

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool valid() const { return lo <= hi; }
};

}  // namespace

void paint_chart(QPainter& p, const Chart& chart) {
  Range xr, yr;
  bool bars = false;
  std::size_t bar_series = 0;
  for (const auto& s : chart.series) {
    if (s.x.size() != s.y.size()) throw BadInput("chart series \"" + s.label + "\": x and y differ in size");
    if ((!s.y_low.empty() && s.y_low.size() != s.y.size()) || (!s.y_high.empty() && s.y_high.size() != s.y.size()))
      throw BadInput("chart series \"" + s.label + "\": error bars and y differ in size");
    if (!s.bar_labels.empty() && s.bar_labels.size() != s.y.size())
      throw BadInput("chart series \"" + s.label + "\": bar labels and y differ in size");
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xr.add(s.x[i]);
      yr.add(s.y[i]);
      if (!s.y_low.empty()) yr.add(s.y_low[i]);
      if (!s.y_high.empty()) yr.add(s.y_high[i]);
    }
    if (s.style == ChartSeries::Style::bars) {
      bars = true;
      ++bar_series;
    }
  }
  if (!xr.valid() || !yr.valid()) throw BadInput("chart \"" + chart.title + "\": no finite point to draw");
  if (bars) {
    yr.add(0.0);  // bars stand on zero
    xr.add(xr.lo - 0.5);
    xr.add(xr.hi + 0.5);
  }
  if (!chart.x_categories.empty()) {
    xr.add(-0.5);
    xr.add(double(chart.x_categories.size()) - 0.5);
  }
  auto pad = [](Range& r) {
    const double span = r.hi - r.lo;
    const double margin = span > 0 ? 0.04 * span : std::max(1.0, std::abs(r.lo) * 0.1);
    r.lo -= margin;
    r.hi += margin;
  };
  if (chart.x_categories.empty() && !bars) pad(xr);
  pad(yr);
  if (chart.x_min) xr.lo = *chart.x_min;
  if (chart.x_max) xr.hi = *chart.x_max;
  if (chart.y_min) yr.lo = *chart.y_min;
  if (chart.y_max) yr.hi = *chart.y_max;
  if (!(xr.hi > xr.lo) || !(yr.hi > yr.lo)) throw BadInput("chart \"" + chart.title + "\": empty axis range");

  p.fillRect(QRectF(0, 0, chart.width_px, chart.height_px), Qt::white);
  p.setRenderHint(QPainter::Antialiasing, true);
  QFont font("DejaVu Sans");
  font.setPixelSize(13);
  p.setFont(font);
  const QFontMetrics fm(font);

  // The legend sits in a column right of the plot, so it can never cover a data point.
  int legend_text_px = 0;
  bool has_legend = false;
  for (const auto& s : chart.series) {
    if (s.label.empty()) continue;
    has_legend = true;
    legend_text_px = std::max(legend_text_px, fm.horizontalAdvance(QString::fromStdString(s.label)));
  }
  const int legend_width = has_legend ? legend_text_px + 40 : 0;
  const int left = 80, right = has_legend ? 24 + legend_width + 12 : 24, top = chart.title.empty() ? 20 : 46,
            bottom = 64;
  if (chart.width_px - left - right < 200) {
    throw BadInput("chart \"" + chart.title + "\": legend labels too long for a " + std::to_string(chart.width_px) +
                   " px wide chart");
  }
  const QRectF plot(left, top, chart.width_px - left - right, chart.height_px - top - bottom);
  auto px = [&](double x) { return plot.left() + (x - xr.lo) / (xr.hi - xr.lo) * plot.width(); };
  auto py = [&](double y) { return plot.bottom() - (y - yr.lo) / (yr.hi - yr.lo) * plot.height(); };

  // Grid, ticks and tick labels.
  const QPen grid(QColor(225, 225, 225), 1), axis(Qt::black, 1);
  const double ys = nice_step(yr.hi - yr.lo, 8);
  for (double y = std::ceil(yr.lo / ys) * ys; y <= yr.hi + ys * 1e-9; y += ys) {
    p.setPen(grid);
    p.drawLine(QPointF(plot.left(), py(y)), QPointF(plot.right(), py(y)));
    p.setPen(axis);
    const QString t = number_text(y, ys);
    p.drawText(QPointF(plot.left() - 8 - fm.horizontalAdvance(t), py(y) + fm.ascent() / 2.0 - 1), t);
  }
  if (!chart.x_categories.empty()) {
    for (std::size_t i = 0; i < chart.x_categories.size(); ++i) {
      const QString t = QString::fromStdString(chart.x_categories[i]);
      p.setPen(axis);
      p.drawText(QPointF(px(double(i)) - fm.horizontalAdvance(t) / 2.0, plot.bottom() + 6 + fm.ascent()), t);
    }
  } else {
    const double xs = nice_step(xr.hi - xr.lo, 10);
    for (double x = std::ceil(xr.lo / xs) * xs; x <= xr.hi + xs * 1e-9; x += xs) {
      p.setPen(grid);
      p.drawLine(QPointF(px(x), plot.top()), QPointF(px(x), plot.bottom()));
      p.setPen(axis);
      const QString t = number_text(x, xs);
      p.drawText(QPointF(px(x) - fm.horizontalAdvance(t) / 2.0, plot.bottom() + 6 + fm.ascent()), t);
    }
  }
  p.setPen(axis);
  p.drawRect(plot);

  // Series, clipped to the plot area.
  p.save();
  p.setClipRect(plot);
  std::size_t palette = 0, bar_index = 0;
  std::vector<std::pair<QString, std::pair<QColor, ChartSeries::Style>>> legend;
  for (const auto& s : chart.series) {
    const QColor c = colour(s.color_rgb ? s.color_rgb : kPalette[palette++ % std::size(kPalette)]);
    if (!s.label.empty()) legend.push_back({QString::fromStdString(s.label), {c, s.style}});
    switch (s.style) {
      case ChartSeries::Style::line: {
        QPainterPath path;
        bool open = false;
        for (std::size_t i = 0; i < s.x.size(); ++i) {
          if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
            open = false;
            continue;
          }
          if (open)
            path.lineTo(px(s.x[i]), py(s.y[i]));
          else
            path.moveTo(px(s.x[i]), py(s.y[i]));
          open = true;
        }
        p.setPen(QPen(c, s.width_px));
        p.setBrush(Qt::NoBrush);
        p.drawPath(path);
        break;
      }
      case ChartSeries::Style::points: {
        p.setPen(QPen(c, 1));
        p.setBrush(c);
        const double r = 1.5 * s.width_px;
        for (std::size_t i = 0; i < s.x.size(); ++i)
          if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) p.drawEllipse(QPointF(px(s.x[i]), py(s.y[i])), r, r);
        break;
      }
      case ChartSeries::Style::bars: {
        const double slot = 0.8 / double(std::max<std::size_t>(bar_series, 1));
        const double offset = -0.4 + slot * (double(bar_index) + 0.5);
        p.setPen(QPen(c.darker(130), 1));
        p.setBrush(c);
        for (std::size_t i = 0; i < s.x.size(); ++i) {
          if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
          const double x0 = px(s.x[i] + offset - 0.45 * slot), x1 = px(s.x[i] + offset + 0.45 * slot);
          p.drawRect(QRectF(QPointF(x0, py(std::max(s.y[i], 0.0))), QPointF(x1, py(std::min(s.y[i], 0.0)))));
        }
        break;
      }
    }
    if (!s.y_low.empty() || !s.y_high.empty()) {
      const double offset = s.style == ChartSeries::Style::bars
                                ? -0.4 + 0.8 / double(std::max<std::size_t>(bar_series, 1)) * (double(bar_index) + 0.5)
                                : 0.0;
      p.setPen(QPen(s.style == ChartSeries::Style::bars ? QColor(Qt::black) : c, 1.5));
      for (std::size_t i = 0; i < s.y.size(); ++i) {
        const double lo = s.y_low.empty() ? s.y[i] : s.y_low[i], hi = s.y_high.empty() ? s.y[i] : s.y_high[i];
        if (!std::isfinite(s.x[i]) || !std::isfinite(lo) || !std::isfinite(hi)) continue;
        const double x = px(s.x[i] + offset);
        p.drawLine(QPointF(x, py(lo)), QPointF(x, py(hi)));
        p.drawLine(QPointF(x - 5, py(lo)), QPointF(x + 5, py(lo)));
        p.drawLine(QPointF(x - 5, py(hi)), QPointF(x + 5, py(hi)));
      }
    }
    if (s.style == ChartSeries::Style::bars) ++bar_index;
  }
  p.restore();

  // Bar labels (n, or "n/a" for a measure with no cases) stand inside each bar from its foot, so
  // neighbouring bars' labels never collide: across when the bar is wide enough, upright
  // otherwise; above a bar too short to hold them, and on the baseline where a bar is missing.
  {
    QFont small = font;
    small.setPixelSize(11);
    p.setFont(small);
    const QFontMetrics sm(small);
    std::size_t index = 0;
    const double slot = 0.8 / double(std::max<std::size_t>(bar_series, 1));
    for (const auto& s : chart.series) {
      if (s.style != ChartSeries::Style::bars) continue;
      const double offset = -0.4 + slot * (double(index++) + 0.5);
      for (std::size_t i = 0; i < s.bar_labels.size(); ++i) {
        if (s.bar_labels[i].empty() || !std::isfinite(s.x[i])) continue;
        const QString t = QString::fromStdString(s.bar_labels[i]);
        const double bar_w = std::abs(px(s.x[i] + offset + 0.45 * slot) - px(s.x[i] + offset - 0.45 * slot));
        const double foot = py(std::max(yr.lo, 0.0));
        const bool has_bar = std::isfinite(s.y[i]);
        const double bar_h = has_bar ? foot - py(std::min(std::max(s.y[i], 0.0), yr.hi)) : 0.0;
        const bool across = sm.horizontalAdvance(t) + 4 <= bar_w;
        const double extent = (across ? sm.height() : sm.horizontalAdvance(t)) + 6;
        const bool inside = has_bar && bar_h >= extent;
        const double base = inside ? foot - 3 : foot - bar_h - 3;  // bottom of the text
        p.setPen(inside ? QColor(Qt::white) : has_bar ? QColor(Qt::black) : QColor(150, 40, 40));
        const double cx = px(s.x[i] + offset);
        if (across) {
          p.drawText(QPointF(cx - sm.horizontalAdvance(t) / 2.0, base - sm.descent()), t);
        } else {
          p.save();
          p.translate(cx + sm.ascent() / 2.0 - 1, base);
          p.rotate(-90);
          p.drawText(QPointF(0, 0), t);
          p.restore();
        }
      }
    }
    p.setFont(font);
  }

  // Labels, title and legend.
  p.setPen(axis);
  if (!chart.x_label.empty()) {
    const QString t = QString::fromStdString(chart.x_label);
    p.drawText(QPointF(plot.center().x() - fm.horizontalAdvance(t) / 2.0, chart.height_px - 14), t);
  }
  if (!chart.y_label.empty()) {
    const QString t = QString::fromStdString(chart.y_label);
    p.save();
    p.translate(18, plot.center().y() + fm.horizontalAdvance(t) / 2.0);
    p.rotate(-90);
    p.drawText(QPointF(0, fm.ascent()), t);
    p.restore();
  }
  if (!chart.title.empty()) {
    QFont bold = font;
    bold.setPixelSize(16);
    bold.setBold(true);
    p.setFont(bold);
    const QString t = QString::fromStdString(chart.title);
    p.drawText(QPointF(plot.center().x() - QFontMetrics(bold).horizontalAdvance(t) / 2.0, 28), t);
    p.setFont(font);
  }
  if (!legend.empty()) {
    const double line_h = fm.height() + 4;
    const QRectF box(plot.right() + 12, plot.top(), legend_width, line_h * double(legend.size()) + 8);
    p.setPen(QPen(QColor(180, 180, 180), 1));
    p.setBrush(QColor(255, 255, 255, 230));
    p.drawRect(box);
    for (std::size_t i = 0; i < legend.size(); ++i) {
      const auto& [text, style] = legend[i];
      const double y = box.top() + 4 + line_h * double(i) + line_h / 2;
      if (style.second == ChartSeries::Style::line) {
        p.setPen(QPen(style.first, 2.5));
        p.drawLine(QPointF(box.left() + 6, y), QPointF(box.left() + 26, y));
      } else {
        p.setPen(QPen(style.first, 1));
        p.setBrush(style.first);
        p.drawRect(QRectF(box.left() + 10, y - 5, 10, 10));
      }
      p.setPen(axis);
      p.drawText(QPointF(box.left() + 32, y + fm.ascent() / 2.0 - 1), text);
    }
  }
}

void ensure_chart_application() { ensure_application(); }

QImage render_chart(const Chart& chart) {
  ensure_application();
  QImage image(chart.width_px, chart.height_px, QImage::Format_ARGB32);
  image.fill(Qt::white);
  QPainter p(&image);
  paint_chart(p, chart);
  p.end();
  return image;
}

void write_chart_png(const Chart& chart, const std::filesystem::path& path) {
  const QImage image = render_chart(chart);
  // Encoded in memory, then written through the checked writer: QImage::save's file is closed
  // (and its last buffer written) after it has already returned true.
  QByteArray png;
  QBuffer buffer(&png);
  buffer.open(QIODevice::WriteOnly);
  if (!image.save(&buffer, "PNG")) throw OutputError(path, "the PNG could not be encoded");
  write_file_checked(path, std::string_view(png.constData(), static_cast<std::size_t>(png.size())));
}

}  // namespace palprig::charts
