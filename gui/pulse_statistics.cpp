#include "gui/pulse_statistics.hpp"
#include "gui/counted_text.hpp"

#include <QHeaderView>
#include <QTableWidget>
#include <cmath>

namespace palprig::gui {

namespace {

std::string percent(double confidence) { return std::to_string(static_cast<int>(std::lround(confidence * 100))); }

}  // namespace

charts::Chart pulse_hit_rate_chart(const std::vector<PulseConditionSummary>& rows, double confidence) {
  charts::Chart chart;
  chart.title = "Pulse localisation: hit rate per condition (Wilson " + percent(confidence) + " % intervals)";
  chart.y_label = "hit rate";
  chart.y_min = 0.0;
  chart.y_max = 1.0;
  charts::ChartSeries bars;
  bars.style = charts::ChartSeries::Style::bars;
  for (const PulseConditionSummary& r : rows) {
    chart.x_categories.push_back(r.condition);
    bars.x.push_back(double(bars.x.size()));
    bars.y.push_back(r.hit_rate);
    bars.y_low.push_back(r.hit_low);
    bars.y_high.push_back(r.hit_high);
    bars.bar_labels.push_back("n=" + std::to_string(r.trials));
  }
  chart.series.push_back(std::move(bars));
  return chart;
}

charts::Chart pulse_distance_chart(const std::vector<PulseConditionSummary>& rows) {
  charts::Chart chart;
  chart.title = "Distance from the mark to the artery (median, quartiles; answered trials)";
  chart.y_label = "distance mm";
  chart.y_min = 0.0;
  charts::ChartSeries bars;
  bars.style = charts::ChartSeries::Style::bars;
  for (const PulseConditionSummary& r : rows) {
    chart.x_categories.push_back(r.condition);
    bars.x.push_back(double(bars.x.size()));
    bars.y.push_back(r.distance_median_mm);  // NaN (no answered trial): no bar, "n/a"
    bars.y_low.push_back(r.distance_q1_mm);
    bars.y_high.push_back(r.distance_q3_mm);
    bars.bar_labels.push_back(r.answered > 0 ? "n=" + std::to_string(r.answered) : "n/a");
  }
  chart.series.push_back(std::move(bars));
  return chart;
}

void fill_pulse_table(QTableWidget& table, const std::vector<PulseConditionSummary>& rows, double confidence) {
  table.clear();
  table.setColumnCount(pulse_column_count);
  table.setHorizontalHeaderLabels({"Condition", "Trials", "Answered", "Hits",
                                   QString("Hit rate [%1 % CI]").arg(QString::fromStdString(percent(confidence))),
                                   "Distance mean mm", "Distance median mm", "Distance IQR mm"});
  table.setRowCount(static_cast<int>(rows.size()));
  for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
    const PulseConditionSummary& r = rows[static_cast<std::size_t>(i)];
    const QStringList cells = {
        QString::fromStdString(r.condition),
        QString::number(r.trials),
        QString::number(r.answered),
        QString::number(r.hits),
        QString("%1 [%2, %3]").arg(number_text(r.hit_rate, 3), number_text(r.hit_low, 3), number_text(r.hit_high, 3)),
        number_text(r.distance_mean_mm, 2),
        number_text(r.distance_median_mm, 2),
        number_text(r.distance_iqr_mm, 2)};
    for (int c = 0; c < pulse_column_count; ++c) table.setItem(i, c, new QTableWidgetItem(cells[c]));
  }
  table.horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
}

}  // namespace palprig::gui
