#include "charts/chart_png.hpp"
// A Chart built as a QCustomPlot and drawn: ranges, dodged categories, markers, error bars,
// labels and the legend. About 400 lines: the one drawing every chart kind shares.

#include <QtCore/QBuffer>
#include <QtCore/QByteArray>
#include <QtCore/QThread>
#include <QtGui/QImage>
#include <QtWidgets/QApplication>
#include <qcustomplot.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/error.hpp"
#include "io/checked_output.hpp"

namespace palprig::charts {

namespace {

// QCustomPlot is a widget, which needs a QApplication; the offscreen platform needs no display.
// A GUI that already runs keeps its own application.
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

void require_application_thread() {
  ensure_chart_application();
  if (QThread::currentThread() != QCoreApplication::instance()->thread())
    throw std::logic_error("charts are drawn on the application's thread (QCustomPlot is a widget)");
  if (!qobject_cast<QApplication*>(QCoreApplication::instance()))
    throw std::logic_error("charts need a QApplication (QCustomPlot is a widget), not a QGuiApplication");
}

// Okabe and Ito's colour-blind-safe palette, and marker shapes and dashes that tell series
// apart in grey as well.
constexpr unsigned kPalette[] = {0x0072B2, 0xD55E00, 0x009E73, 0xCC79A7, 0xE69F00, 0x56B4E9, 0x000000, 0x999999};
constexpr Marker kMarkers[] = {
    Marker::circle, Marker::square, Marker::diamond, Marker::triangle, Marker::inverted_triangle,
    Marker::cross,  Marker::plus};

QColor colour(unsigned rgb) { return QColor(int((rgb >> 16) & 0xff), int((rgb >> 8) & 0xff), int(rgb & 0xff)); }

QFont font_px(int px, bool bold = false) {
  QFont f("DejaVu Sans");
  f.setPixelSize(px);
  f.setBold(bold);
  return f;
}

QCPScatterStyle::ScatterShape shape_of(Marker m) {
  switch (m) {
    case Marker::none: return QCPScatterStyle::ssNone;
    case Marker::circle: return QCPScatterStyle::ssCircle;
    case Marker::square: return QCPScatterStyle::ssSquare;
    case Marker::diamond: return QCPScatterStyle::ssDiamond;
    case Marker::triangle: return QCPScatterStyle::ssTriangle;
    case Marker::inverted_triangle: return QCPScatterStyle::ssTriangleInverted;
    case Marker::cross: return QCPScatterStyle::ssCross;
    case Marker::plus: return QCPScatterStyle::ssPlus;
  }
  return QCPScatterStyle::ssCircle;
}

// Filled markers (crosses and pluses have no inside).
QCPScatterStyle marker_style(Marker m, const QColor& c, double size) {
  const bool open = m == Marker::cross || m == Marker::plus;
  return QCPScatterStyle(shape_of(m), QPen(c, open ? 2.0 : 1.2), open ? QBrush(Qt::NoBrush) : QBrush(c), size);
}

Qt::PenStyle pen_style(Dash d) {
  return d == Dash::dashed ? Qt::DashLine : d == Dash::dotted ? Qt::DotLine : Qt::SolidLine;
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

bool dodged(const Chart& c, const ChartSeries& s) {
  return !c.x_categories.empty() && s.style != ChartSeries::Style::line;
}

// Lines of a label ("0.962\nn=26").
int line_count(const std::string& text) { return 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

// Ticks only within [lo, hi] (a proportion axis padded beyond 1 for its labels shows no "1.05").
class BoundedTicker : public QCPAxisTicker {
 public:
  BoundedTicker(double lo, double hi) : lo_(lo), hi_(hi) {}

 protected:
  QVector<double> createTickVector(double step, const QCPRange& range) override {
    QVector<double> ticks = QCPAxisTicker::createTickVector(step, range), kept;
    for (double t : ticks)
      if (t >= lo_ - 1e-9 * step && t <= hi_ + 1e-9 * step) kept.push_back(t);
    return kept;
  }

 private:
  double lo_, hi_;
};

// Pixels the plot's axis rectangle is likely to have vertically (for the room labels need).
double plot_height_px(const Chart& c, int legend_rows) {
  return std::max(80.0, double(c.height_px) - (c.title.empty() ? 0 : 30) - 58 - legend_rows * 20.0 - 16);
}

class ChartBuilder {
 public:
  ChartBuilder(QCustomPlot& plot, const Chart& chart) : plot_(plot), c_(chart) {}

  void build() {
    validate_chart(c_);
    for (const auto& s : c_.series)
      if (dodged(c_, s)) ++dodged_count_;
    plot_.setBackground(Qt::white);
    plot_.setAntialiasedElements(QCP::aeAll);
    // A little room at the right and bottom edges: the last tick label and the legend's last
    // line's descenders stay inside the picture.
    plot_.plotLayout()->setMargins(QMargins(2, 2, 10, 8));
    if (!c_.title.empty()) {
      plot_.plotLayout()->insertRow(0);
      auto* title = new QCPTextElement(&plot_, QString::fromStdString(c_.title), font_px(14, true));
      plot_.plotLayout()->addElement(0, 0, title);
    }
    axes();
    std::size_t palette = 0, markers = 0, dodge = 0;
    for (const auto& s : c_.series) {
      const QColor col = colour(s.color_rgb ? s.color_rgb : kPalette[palette++ % std::size(kPalette)]);
      Marker m = s.marker;
      if (s.style == ChartSeries::Style::points && m == Marker::none) m = kMarkers[markers++ % std::size(kMarkers)];
      const double offset = dodged(c_, s) ? dodge_offset(dodge++) : 0.0;
      switch (s.style) {
        case ChartSeries::Style::line: add_line(s, col, m); break;
        case ChartSeries::Style::points: add_points(s, col, m, offset); break;
        case ChartSeries::Style::bars: add_bars(s, col, offset); break;
      }
      add_point_labels(s, offset);
    }
    for (const ChartText& t : c_.annotations) add_text(t.x, t.y, t.text, t.align, t.offset_px, colour(t.color_rgb));
    legend();
    ranges();
  }

 private:
  double slot() const { return 0.8 / double(std::max(dodged_count_, 1)); }
  double dodge_offset(std::size_t i) const {
    return dodged_count_ > 1 ? -0.4 + slot() * (static_cast<double>(i) + 0.5) : 0.0;
  }

  void axes() {
    for (QCPAxis* a : {plot_.xAxis, plot_.yAxis}) {
      a->setTickLabelFont(font_px(12));
      a->setLabelFont(font_px(13));
      a->setBasePen(QPen(Qt::black, 1));
      a->setTickPen(QPen(Qt::black, 1));
      a->setSubTickPen(QPen(Qt::black, 1));
      a->setTickLength(0, 5);  // ticks outside the frame: the plot area is the data's
      a->setSubTickLength(0, 3);
      a->grid()->setPen(QPen(QColor(225, 225, 225), 1));
      a->grid()->setZeroLinePen(Qt::NoPen);
    }
    plot_.xAxis->setLabel(QString::fromStdString(c_.x_label));
    plot_.yAxis->setLabel(QString::fromStdString(c_.y_label));
    // The frame's other two sides, without ticks: the plot reads as a closed box.
    for (QCPAxis* a : {plot_.xAxis2, plot_.yAxis2}) {
      a->setVisible(true);
      a->setTicks(false);
      a->setTickLabels(false);
      a->setBasePen(QPen(Qt::black, 1));
    }
    if (!c_.x_categories.empty()) {
      QSharedPointer<QCPAxisTickerText> ticker(new QCPAxisTickerText);
      for (std::size_t i = 0; i < c_.x_categories.size(); ++i)
        ticker->addTick(double(i), QString::fromStdString(c_.x_categories[i]));
      plot_.xAxis->setTicker(ticker);
      plot_.xAxis->setSubTicks(false);
      plot_.xAxis->grid()->setVisible(false);
    } else if (c_.x_whole_numbers) {
      // Steps of 1, 2, 5, 10, ... cases: QCustomPlot's fixed ticker scaled by whole multiples.
      QSharedPointer<QCPAxisTickerFixed> ticker(new QCPAxisTickerFixed);
      ticker->setTickStep(1.0);
      ticker->setScaleStrategy(QCPAxisTickerFixed::ssMultiples);
      plot_.xAxis->setTicker(ticker);
      plot_.xAxis->setSubTicks(false);
    }
  }

  void track(double x, double y) {
    xr_.add(x);
    yr_.add(y);
  }

  // A line broken at non-finite points: one curve per finite run (QCPCurve keeps the order of
  // the points, so loops such as a hysteresis model's are drawn as they go).
  void add_line(const ChartSeries& s, const QColor& col, Marker m) {
    QPen pen(col, s.width_px, pen_style(s.dash));
    pen.setCapStyle(Qt::FlatCap);
    bool first = true;
    std::size_t i = 0;
    while (i < s.x.size()) {
      QVector<double> xs, ys;
      for (; i < s.x.size() && std::isfinite(s.x[i]) && std::isfinite(s.y[i]); ++i) {
        xs.push_back(s.x[i]);
        ys.push_back(s.y[i]);
        track(s.x[i], s.y[i]);
      }
      if (!xs.empty()) {
        auto* curve = new QCPCurve(plot_.xAxis, plot_.yAxis);
        curve->setData(xs, ys);
        curve->setPen(pen);
        if (m != Marker::none) {
          curve->setScatterStyle(marker_style(m, col, s.marker_px));
          largest_marker_px_ = std::max(largest_marker_px_, s.marker_px);
        }
        name(curve, first ? s.label : std::string());
        first = false;
      }
      ++i;
    }
    add_error_bars(s, col, 0.0, nullptr);
  }

  void add_points(const ChartSeries& s, const QColor& col, Marker m, double offset) {
    const bool sized = !s.marker_sizes_px.empty();
    QCPGraph* all = nullptr;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      track(s.x[i] + offset, s.y[i]);
      largest_marker_px_ = std::max(largest_marker_px_, sized ? s.marker_sizes_px[i] : s.marker_px);
      if (sized || !all) {
        all = plot_.addGraph();
        all->setLineStyle(QCPGraph::lsNone);
        all->setScatterStyle(marker_style(m, col, sized ? s.marker_sizes_px[i] : s.marker_px));
        name(all, std::string());
      }
      all->addData(s.x[i] + offset, s.y[i]);
      if (sized) add_error_bar(s, i, col, offset, all);
    }
    if (!sized) add_error_bars(s, col, offset, all);
    // The legend entry: one marker of the series' usual size (points of several sizes get one).
    if (!s.label.empty()) {
      auto* entry = plot_.addGraph();
      entry->setLineStyle(QCPGraph::lsNone);
      entry->setScatterStyle(marker_style(m, col, s.marker_px));
      entry->setName(QString::fromStdString(s.label));
    }
  }

  void add_bars(const ChartSeries& s, const QColor& col, double offset) {
    auto* bars = new QCPBars(plot_.xAxis, plot_.yAxis);
    bars->setWidth(0.9 * (dodged_count_ > 0 && !c_.x_categories.empty() ? slot() : 0.8));
    bars->setPen(QPen(col.darker(130), 1));
    bars->setBrush(col);
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      bars->addData(s.x[i] + offset, s.y[i]);
      track(s.x[i] + offset - 0.5 * bars->width(), s.y[i]);
      track(s.x[i] + offset + 0.5 * bars->width(), 0.0);  // bars stand on zero
    }
    name(bars, s.label);
    add_error_bars(s, QColor(Qt::black), offset, bars);
  }

  void name(QCPAbstractPlottable* p, const std::string& label) {
    if (label.empty())
      p->removeFromLegend();
    else
      p->setName(QString::fromStdString(label));
  }

  // Error bars on every point of a series (vertical and horizontal), drawn over `owner`.
  void add_error_bars(const ChartSeries& s, const QColor& col, double offset, QCPAbstractPlottable* owner) {
    for (std::size_t i = 0; i < s.x.size(); ++i) add_error_bar(s, i, col, offset, owner);
  }

  void add_error_bar(const ChartSeries& s, std::size_t i, const QColor& col, double offset, QCPAbstractPlottable*) {
    const double x = s.x[i] + offset, y = s.y[i];
    if (!std::isfinite(x)) return;
    QPen pen(col, 1.5);
    auto segment = [&](double x0, double y0, double x1, double y1, bool vertical) {
      auto* line = new QCPItemLine(&plot_);
      line->start->setCoords(x0, y0);
      line->end->setCoords(x1, y1);
      line->setPen(pen);
      QCPLineEnding cap(QCPLineEnding::esBar, 10);
      line->setHead(cap);
      line->setTail(cap);
      (void)vertical;
      track(x0, y0);
      track(x1, y1);
    };
    if (!s.y_low.empty() && !s.y_high.empty() && std::isfinite(s.y_low[i]) && std::isfinite(s.y_high[i]))
      segment(x, s.y_low[i], x, s.y_high[i], true);
    if (!s.x_low.empty() && !s.x_high.empty() && std::isfinite(s.x_low[i]) && std::isfinite(s.x_high[i]) &&
        std::isfinite(y))
      segment(s.x_low[i] + offset, y, s.x_high[i] + offset, y, false);
  }

  // Each point's label: above its upper whisker (or the point, or the top of its bar); a point
  // without a value gets its label ("n/a") just above the axis' foot, where it was missing.
  void add_point_labels(const ChartSeries& s, double offset) {
    for (std::size_t i = 0; i < s.point_labels.size() && i < s.x.size(); ++i) {
      if (s.point_labels[i].empty() || !std::isfinite(s.x[i])) continue;
      const double top = !s.y_high.empty() && std::isfinite(s.y_high[i]) ? s.y_high[i] : s.y[i];
      if (std::isfinite(top)) {
        label_lines_ = std::max(label_lines_, line_count(s.point_labels[i]));
        labelled_top_ = std::max(labelled_top_, top);
        add_text(s.x[i] + offset, top, s.point_labels[i], ChartText::Align::above, 4, QColor(Qt::black));
      } else {
        missing_.push_back({s.x[i] + offset, s.point_labels[i]});
      }
    }
  }

  void add_text(double x, double y, const std::string& text, ChartText::Align align, double offset, const QColor& col) {
    auto* t = new QCPItemText(&plot_);
    t->position->setCoords(x, y);
    t->setText(QString::fromStdString(text));
    t->setFont(font_px(11));
    t->setColor(col);
    t->setTextAlignment(align == ChartText::Align::left    ? Qt::AlignRight
                        : align == ChartText::Align::right ? Qt::AlignLeft
                                                           : Qt::AlignHCenter);
    const int pad = static_cast<int>(std::lround(offset));
    switch (align) {
      case ChartText::Align::right:
        t->setPositionAlignment(Qt::AlignLeft | Qt::AlignVCenter);
        t->setPadding(QMargins(pad, 0, 0, 0));
        break;
      case ChartText::Align::left:
        t->setPositionAlignment(Qt::AlignRight | Qt::AlignVCenter);
        t->setPadding(QMargins(0, 0, pad, 0));
        break;
      case ChartText::Align::above:
        t->setPositionAlignment(Qt::AlignHCenter | Qt::AlignBottom);
        t->setPadding(QMargins(0, 0, 0, pad));
        break;
      case ChartText::Align::below:
        t->setPositionAlignment(Qt::AlignHCenter | Qt::AlignTop);
        t->setPadding(QMargins(0, pad, 0, 0));
        break;
      case ChartText::Align::center: t->setPositionAlignment(Qt::AlignCenter); break;
    }
    xr_.add(x);
    yr_.add(y);
  }

  void legend() {
    int entries = 0, longest = 0;
    const QFontMetrics fm(font_px(12));
    for (int i = 0; i < plot_.legend->itemCount(); ++i) {
      auto* item = qobject_cast<QCPPlottableLegendItem*>(plot_.legend->item(i));
      if (!item) continue;
      ++entries;
      longest = std::max(longest, fm.horizontalAdvance(item->plottable()->name()));
    }
    if (entries == 0) {
      plot_.legend->setVisible(false);
      return;
    }
    plot_.legend->setVisible(true);
    plot_.legend->setFont(font_px(12));
    plot_.legend->setIconSize(28, 14);
    plot_.legend->setBorderPen(Qt::NoPen);
    plot_.legend->setBrush(Qt::NoBrush);
    // Under the plot, as many entries a row as fit the width: never over the data.
    const int per_entry = longest + 28 + 24;
    columns_ = std::clamp((c_.width_px - 40) / std::max(per_entry, 1), 1, entries);
    legend_rows_ = (entries + columns_ - 1) / columns_;
    // The wrap first: setFillOrder(..., true) rearranges the items by it.
    plot_.legend->setWrap(columns_);
    plot_.legend->setFillOrder(QCPLayoutGrid::foColumnsFirst, true);
    plot_.legend->setColumnSpacing(18);
    const int row = plot_.plotLayout()->rowCount();
    plot_.plotLayout()->addElement(row, 0, plot_.legend);
    plot_.plotLayout()->setRowStretchFactor(row, 0.001);
    // Its rows' height asked for outright: the grid's own hint came up a few pixels short of the
    // last row's descenders.
    const int row_px = QFontMetrics(font_px(12)).height() + 6;
    plot_.legend->setMinimumSize(0, legend_rows_ * row_px + 10);
  }

  void ranges() {
    Range xr = xr_, yr = yr_;
    if (!c_.x_categories.empty()) {
      xr.add(-0.5);
      xr.add(double(c_.x_categories.size()) - 0.5);
    }
    if (!xr.valid() || !yr.valid()) throw BadInput("chart \"" + c_.title + "\": no finite point to draw");
    auto pad = [](Range& r, double share) {
      const double span = r.hi - r.lo;
      const double margin = span > 0 ? share * span : std::max(1.0, std::abs(r.lo) * 0.1);
      r.lo -= margin;
      r.hi += margin;
    };
    if (c_.x_categories.empty()) pad(xr, 0.04);
    const double data_y_hi = yr.hi;
    pad(yr, 0.05);
    // The chart's own ends are where the data's axis ends (and its ticks); labels above the
    // highest labelled point get room beyond them, so nothing is cut by the frame.
    if (c_.x_min) xr.lo = *c_.x_min;
    if (c_.x_max) xr.hi = *c_.x_max;
    if (c_.y_min) yr.lo = *c_.y_min;
    if (c_.y_max) yr.hi = *c_.y_max;
    if (!(xr.hi > xr.lo) || !(yr.hi > yr.lo)) throw BadInput("chart \"" + c_.title + "\": empty axis range");
    const double tick_lo = yr.lo, tick_hi = c_.y_max ? *c_.y_max : std::max(data_y_hi, yr.lo);
    const double plot_px = plot_height_px(c_, legend_rows_);
    // Room for the largest marker's half and a whisker's cap beyond the highest and lowest
    // point, also where the chart's own ends sit on them (a proportion of 1 on an axis to 1).
    if (plot_px > 2 * largest_marker_px_) {
      const double edge_px = 0.5 * largest_marker_px_ + 3;
      yr.hi = std::max(yr.hi, (yr_.hi * plot_px - edge_px * yr.lo) / (plot_px - edge_px));
      yr.lo = std::min(yr.lo, (yr_.lo * plot_px - edge_px * yr.hi) / (plot_px - edge_px));
    }
    if (label_lines_ > 0) {
      const double need_px = label_lines_ * 14.0 + 10;
      // The top T with need_px between the label's anchor L and T: (T - L) / (T - lo) = need / plot.
      if (plot_px > need_px) yr.hi = std::max(yr.hi, (labelled_top_ * plot_px - need_px * yr.lo) / (plot_px - need_px));
    }
    plot_.xAxis->setRange(xr.lo, xr.hi);
    plot_.yAxis->setRange(yr.lo, yr.hi);
    plot_.yAxis->setTicker(QSharedPointer<QCPAxisTicker>(new BoundedTicker(tick_lo, tick_hi)));
    for (const auto& [x, text] : missing_) add_text(x, yr.lo, text, ChartText::Align::above, 4, QColor(150, 40, 40));
  }

  QCustomPlot& plot_;
  const Chart& c_;
  int dodged_count_ = 0, columns_ = 1, legend_rows_ = 0, label_lines_ = 0;
  double largest_marker_px_ = 6;  // of the points drawn, for the room at the axis' ends
  double labelled_top_ = -std::numeric_limits<double>::infinity();
  Range xr_, yr_;
  std::vector<std::pair<double, std::string>> missing_;
};

void draw(QCPPainter& painter, const Chart& chart) {
  require_application_thread();
  QCustomPlot plot;
  ChartBuilder(plot, chart).build();
  plot.toPainter(&painter, chart.width_px, chart.height_px);
}

}  // namespace

void validate_chart(const Chart& chart) {
  bool any = false;
  for (const auto& s : chart.series) {
    if (s.x.size() != s.y.size()) throw BadInput("chart series \"" + s.label + "\": x and y differ in size");
    for (const auto* v : {&s.y_low, &s.y_high, &s.x_low, &s.x_high})
      if (!v->empty() && v->size() != s.y.size())
        throw BadInput("chart series \"" + s.label + "\": error bars and y differ in size");
    if (!s.point_labels.empty() && s.point_labels.size() != s.y.size())
      throw BadInput("chart series \"" + s.label + "\": point labels and y differ in size");
    if (!s.marker_sizes_px.empty() && s.marker_sizes_px.size() != s.y.size())
      throw BadInput("chart series \"" + s.label + "\": marker sizes and y differ in size");
    for (std::size_t i = 0; i < s.x.size(); ++i) any = any || (std::isfinite(s.x[i]) && std::isfinite(s.y[i]));
  }
  if (!any) throw BadInput("chart \"" + chart.title + "\": no finite point to draw");
  if (chart.width_px < 200 || chart.height_px < 150 || chart.width_px > 10000 || chart.height_px > 10000)
    throw BadInput("chart \"" + chart.title + "\": a size of 200 x 150 to 10000 x 10000 px");
}

void ensure_chart_application() {
  if (QCoreApplication::instance()) return;
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  previous_handler = qInstallMessageHandler(quiet_runtime_dir_warning);
  static int argc = 1;
  static char name[] = "palprig";
  static char* argv[] = {name, nullptr};
  static QApplication* app = new QApplication(argc, argv);  // lives as long as the process
  (void)app;
}

QImage render_chart(const Chart& chart, double scale) {
  validate_chart(chart);
  require_application_thread();
  QImage image(static_cast<int>(std::lround(chart.width_px * scale)),
               static_cast<int>(std::lround(chart.height_px * scale)), QImage::Format_ARGB32);
  image.fill(Qt::white);
  QCPPainter painter(&image);
  painter.setMode(QCPPainter::pmNoCaching);
  if (scale != 1.0) painter.scale(scale, scale);
  draw(painter, chart);
  painter.end();
  return image;
}

void paint_chart(QPaintDevice& device, const Chart& chart) {
  validate_chart(chart);
  require_application_thread();
  QCPPainter painter(&device);
  painter.setMode(QCPPainter::pmVectorized);
  painter.setMode(QCPPainter::pmNoCaching);
  draw(painter, chart);
  painter.end();
}

void write_chart_png(const Chart& chart, const std::filesystem::path& path) {
  QImage image = render_chart(chart, kPrintScale);
  const int dots_per_meter = static_cast<int>(std::lround(kPrintDotsPerInch / 0.0254));
  image.setDotsPerMeterX(dots_per_meter);
  image.setDotsPerMeterY(dots_per_meter);
  // Encoded in memory, then written through the checked writer: QImage::save's file is closed
  // (and its last buffer written) after it has already returned true.
  QByteArray png;
  QBuffer buffer(&png);
  buffer.open(QIODevice::WriteOnly);
  // Quality 0: zlib's strongest compression (the same pixels in a smaller file).
  if (!image.save(&buffer, "PNG", 0)) throw OutputError(path, "the PNG could not be encoded");
  write_file_checked(path, std::string_view(png.constData(), static_cast<std::size_t>(png.size())));
}

}  // namespace palprig::charts
