#pragma once
// A chart (charts/chart_png.hpp) as a widget: the same drawing as the PNG and SVG files, scaled to
// the widget's size, so what the experimenter sees is what the export writes.
#include <QString>
#include <QWidget>

#include "charts/chart_png.hpp"

namespace palprig::gui {

class ChartView : public QWidget {
  Q_OBJECT
 public:
  explicit ChartView(QWidget* parent = nullptr);
  // Shows `chart`; `empty_text` replaces it while it has nothing to draw.
  void set_chart(charts::Chart chart, const QString& empty_text);
  const charts::Chart& chart() const { return chart_; }
  bool has_data() const;

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  charts::Chart chart_;
  QString empty_text_;
};

}  // namespace palprig::gui
