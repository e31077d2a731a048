#include "gui/pulse_statistics.hpp"
#include "gui/counted_text.hpp"

#include <QHeaderView>
#include <QTableWidget>
#include <cmath>

namespace palprig::gui {

namespace {

std::string percent(double confidence) { return std::to_string(static_cast<int>(std::lround(confidence * 100))); }

}  // namespace

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
