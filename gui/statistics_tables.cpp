#include "gui/statistics_tables.hpp"
#include "gui/counted_text.hpp"

#include <QHeaderView>
#include <QTableWidget>
#include <cmath>

namespace palprig::gui {

namespace {

void set_cell(QTableWidget& table, int row, int column, const QString& text, const QString& tip = {}) {
  auto* item = new QTableWidgetItem(text);
  item->setFlags(Qt::ItemIsSelectable | Qt::ItemIsEnabled);
  if (!tip.isEmpty()) item->setToolTip(tip);
  if (text == QLatin1String("n/a")) item->setForeground(QColor(150, 40, 40));
  table.setItem(row, column, item);
}

void add_rows(QTableWidget& table, const TrialSummary& summary, const QString& prefix) {
  for (const SummaryRow& r : summary.rows) {
    const int row = table.rowCount();
    table.insertRow(row);
    set_cell(table, row, group_column, prefix + QString::fromStdString(r.key.empty() ? "all" : r.key[0]));
    set_cell(
        table, row, trials_column,
        QString::number(r.trials) + (r.unanswered ? QStringLiteral(" (%1 unanswered)").arg(r.unanswered) : QString()));
    set_cell(table, row, tp_column, QString::number(r.counts.tp));
    set_cell(table, row, fn_column, QString::number(r.counts.fn));
    set_cell(table, row, tn_column, r.negatives_counted ? QString::number(r.counts.tn) : QStringLiteral("n/a"),
             r.negatives_counted ? QString() : QStringLiteral("localisation: tumor-free spots are not counted"));
    set_cell(table, row, fp_column, QString::number(r.counts.fp));
    set_cell(table, row, se_column, measure_text(r.measures.se));
    set_cell(table, row, sp_column, measure_text(r.measures.sp));
    set_cell(table, row, ppv_column, measure_text(r.measures.ppv));
    set_cell(table, row, acc_column, measure_text(r.measures.acc));
    set_cell(table, row, rt_column,
             std::isfinite(r.mean_rt_s)
                 ? number_text(r.mean_rt_s, 2) + QStringLiteral(" ± ") + number_text(r.sd_rt_s, 2)
                 : QStringLiteral("n/a"));
    set_cell(table, row, rt_after_column,
             std::isfinite(r.mean_rt_after_stimulus_s)
                 ? number_text(r.mean_rt_after_stimulus_s, 2) + QStringLiteral(" ± ") +
                       number_text(r.sd_rt_after_stimulus_s, 2)
                 : QStringLiteral("n/a"));
    set_cell(
        table, row, rt_reached_column,
        std::isfinite(r.mean_rt_from_reached_s)
            ? number_text(r.mean_rt_from_reached_s, 2) + QStringLiteral(" ± ") + number_text(r.sd_rt_from_reached_s, 2)
            : QStringLiteral("n/a"));
    set_cell(table, row, confidence_column,
             r.rated > 0 ? number_text(r.mean_confidence, 2) + QStringLiteral(" (n=%1)").arg(r.rated)
                         : QStringLiteral("n/a"));
  }
}

}  // namespace

QString measure_text(const Measure& m) {
  if (!m.defined) return QStringLiteral("n/a");
  return QStringLiteral("%1 [%2, %3] n=%4")
      .arg(number_text(m.value), number_text(m.lower), number_text(m.upper))
      .arg(m.n);
}

void fill_measures_table(QTableWidget& table, const TrialStatistics& s) {
  table.clear();
  table.setRowCount(0);
  table.setColumnCount(measure_column_count);
  const int percent = int(std::lround(s.confidence * 100));
  table.setHorizontalHeaderLabels({QObject::tr("group"), QObject::tr("trials"), "TP", "FN", "TN", "FP",
                                   QObject::tr("Se [%1 % Wilson]").arg(percent), "Sp", "PPV", "ACC",
                                   QObject::tr("RT from onset, mean ± sd (s)"),
                                   QObject::tr("RT after stimulus, mean ± sd (s)"),
                                   QObject::tr("RT from reached, mean ± sd (s)"), QObject::tr("confidence mean")});
  // The rating column only when some trial has a rating (as `stats trials` shows it).
  const bool rated = s.by_condition.any_rated;
  add_rows(table, s.by_condition, QObject::tr("condition "));
  add_rows(table, s.by_finger, QObject::tr("finger "));
  add_rows(table, s.by_tumor, QObject::tr("tumor "));
  table.setColumnHidden(confidence_column, !rated);
  table.resizeColumnsToContents();
}

void fill_comparisons_table(QTableWidget& table, const TrialStatistics& s) {
  table.clear();
  table.setRowCount(0);
  table.setColumnCount(5);
  table.setHorizontalHeaderLabels({QObject::tr("comparison"), QObject::tr("conditions"), QObject::tr("values"),
                                   QObject::tr("test"), QObject::tr("result")});
  const double alpha = 1.0 - s.confidence;
  for (const ResponseTimeComparison& c : s.response_times) {
    const int row = table.rowCount();
    table.insertRow(row);
    set_cell(table, row, 0, QObject::tr("response time (Student t, paper 002)"));
    set_cell(table, row, 1, QString::fromStdString(c.first + " vs " + c.second));
    if (!c.test) {
      set_cell(table, row, 2, QStringLiteral("n/a"));
      set_cell(table, row, 3, QStringLiteral("n/a"), QString::fromStdString(c.why_not));
      set_cell(table, row, 4, QString::fromStdString(c.why_not));
      continue;
    }
    const auto& t = *c.test;
    set_cell(table, row, 2,
             QStringLiteral("%1 s (n=%2) vs %3 s (n=%4)")
                 .arg(number_text(t.mean_x, 3))
                 .arg(t.n_x)
                 .arg(number_text(t.mean_y, 3))
                 .arg(t.n_y));
    const QString p_text = t.p < 1e-4 ? QStringLiteral("p < 0.0001") : QStringLiteral("p = ") + number_text(t.p, 4);
    set_cell(table, row, 3, QStringLiteral("t(%1) = %2, %3").arg(number_text(t.df, 0), number_text(t.t, 3), p_text));
    set_cell(table, row, 4, t.p < alpha ? QObject::tr("different (p < %1)").arg(alpha) : QObject::tr("not different"));
  }
  for (const MeasureComparison& c : s.measures) {
    const int row = table.rowCount();
    table.insertRow(row);
    const auto& p = c.comparison;
    set_cell(table, row, 0, QString::fromStdString(c.measure) + QObject::tr(" (combined interval, eq. 10)"));
    set_cell(table, row, 1, QString::fromStdString(c.first + " vs " + c.second));
    set_cell(table, row, 2,
             QStringLiteral("%1 vs %2, difference %3")
                 .arg(number_text(p.first.p), number_text(p.second.p), number_text(p.difference)));
    // Eq. 10: different when |difference| exceeds the combined interval; say which way it went.
    set_cell(table, row, 3,
             QStringLiteral("|difference| %1 combined CI %2")
                 .arg(p.significant ? QStringLiteral(">") : QStringLiteral("<="), number_text(p.combined_interval)));
    set_cell(table, row, 4, p.significant ? QObject::tr("different") : QObject::tr("not different"));
  }
  table.resizeColumnsToContents();
}

}  // namespace palprig::gui
