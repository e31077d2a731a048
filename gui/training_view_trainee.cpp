// TrainingView's trainee part (the rest is training_view.cpp): the picked trainee's standing,
// the benchmark of their level, their sessions with each one's scores, their learning curve and
// CUSUM charts, and a scored session's outcome.
#include <QComboBox>
#include <QLabel>
#include <QTableWidget>

#include "charts/learning_charts.hpp"
#include "gui/chart_view.hpp"
#include "gui/training_view.hpp"

namespace palprig::gui {

namespace {

QString fixed(std::optional<double> v, int decimals) { return v ? QString::number(*v, 'f', decimals) : "n/a"; }

// "tumors found >= 0.90, false marks per case <= 1.00, s per case <= 60.0, 2 sessions in a row"
QString benchmark_text(const LevelBenchmark& b) {
  QStringList parts;
  if (b.found_min) parts << QString("tumors found >= %1").arg(*b.found_min, 0, 'f', 2);
  if (b.false_marks_per_case_max)
    parts << QString("false marks per case <= %1").arg(*b.false_marks_per_case_max, 0, 'f', 2);
  if (b.time_per_case_max_s) parts << QString("s per case <= %1").arg(*b.time_per_case_max_s, 0, 'f', 1);
  if (b.normal_called_min) parts << QString("normal cases called normal >= %1").arg(*b.normal_called_min, 0, 'f', 2);
  parts << QString("%1 sessions in a row").arg(b.consecutive_sessions);
  return parts.join(", ");
}

}  // namespace

void TrainingView::show_trainee() {
  sessions_->setRowCount(0);
  curves_.reset();
  const QString code = selected_trainee();
  const TraineeStanding* t = nullptr;
  for (const auto& s : standings_)
    if (QString::fromStdString(s.trainee) == code) t = &s;
  if (!curriculum_ || t == nullptr) {
    standing_->setText(standings_.empty() ? "No trainee enrolled in this course yet." : "Pick a trainee.");
    show_charts();
    set_buttons();
    return;
  }
  const Curriculum& c = *curriculum_;
  QString text = QString("<b>%1</b>: %2, %3 completed")
                     .arg(code, training_level_text(c, t->standing.level))
                     .arg(t->standing.sessions);
  text += t->standing.sessions == 1 ? " session" : " sessions";
  if (!t->standing.finished) {
    const CurriculumLevel& level = c.levels[static_cast<std::size_t>(t->standing.level)];
    text += QString(", %1 of %2 in a row met.<br>Benchmark: %3")
                .arg(t->standing.consecutive_met)
                .arg(level.benchmark.consecutive_sessions)
                .arg(benchmark_text(level.benchmark).toHtmlEscaped());
  }
  if (t->standing.running_session) text += "<br>An unfinished session: Start next session continues it.";
  standing_->setText(text);
  sessions_->setRowCount(static_cast<int>(t->sessions.size()));
  for (int i = 0; i < static_cast<int>(t->sessions.size()); ++i) {
    const TrainingSessionRecord& r = t->sessions[static_cast<std::size_t>(i)];
    const SessionScores& s = t->scores[static_cast<std::size_t>(i)];
    if (!r.completed()) {
      set_row(sessions_, i,
              {QString::number(i + 1), QString::fromStdString(r.level_name), QString::number(r.cases.size()),
               "unfinished", "", "", "", ""});
      continue;
    }
    set_row(sessions_, i,
            {QString::number(i + 1), QString::fromStdString(r.level_name), QString::number(s.cases.size()),
             QString("%1/%2").arg(s.found()).arg(s.targets()), fixed(s.false_marks_per_case(), 2),
             fixed(s.time_per_case_s(), 1),
             s.normal_cases() ? QString("%1/%2").arg(s.normal_called()).arg(s.normal_cases()) : "n/a",
             r.met_benchmark.value_or(false) ? "met" : "not met"});
  }
  sessions_->resizeColumnsToContents();
  if (sessions_->rowCount() > 0) sessions_->scrollToBottom();
  try {
    curves_ = training_curves(c, *t);
  } catch (const std::exception& e) {
    refuse(e.what());
  }
  show_charts();
  set_buttons();
}

void TrainingView::show_charts() {
  const std::string code = selected_trainee().toStdString();
  if (!curves_) {
    curve_->set_chart({}, "Pick a trainee: their learning curve shows here.");
    cusum_->set_chart({}, "Pick a trainee: their CUSUM charts show here.");
    return;
  }
  const auto measure = static_cast<charts::LearningMeasure>(measure_->currentData().toInt());
  const auto kind = static_cast<stats::CusumChart>(chart_kind_->currentData().toInt());
  curve_->set_chart(charts::learning_curve_chart(*curves_, measure, code),
                    "No completed session with this measure yet.");
  // Without a case the chart would be its limit line alone over an empty axis.
  if (curves_->case_failures.empty())
    cusum_->set_chart({}, "No case completed yet: the chart starts with the trainee's first case.");
  else
    cusum_->set_chart(charts::cusum_chart(*curves_, kind, code), "No case completed yet.");
}

void TrainingView::show_outcome(const TrainingOutcome& out) {
  if (!curriculum_) return;
  const SessionScores& s = out.scores;
  QString text =
      QString("%1's session %2 completed: tumors found %3 (%4 of %5), false marks per case %6, %7 s per case")
          .arg(QString::fromStdString(out.plan.trainee))
          .arg(out.plan.session_number)
          .arg(fixed(s.found_fraction(), 2))
          .arg(s.found())
          .arg(s.targets())
          .arg(fixed(s.false_marks_per_case(), 2))
          .arg(fixed(s.time_per_case_s(), 1));
  if (s.normal_cases() > 0)
    text += QString(", normal cases called normal %1 of %2").arg(s.normal_called()).arg(s.normal_cases());
  QStringList shortfalls;
  for (const auto& f : out.benchmark.shortfalls) shortfalls << QString::fromStdString(f);
  text += out.benchmark.met ? ". Benchmark met" : ". Benchmark not met: " + shortfalls.join("; ");
  if (out.after.level > out.plan.level && out.before.level == out.plan.level)
    text += QString("; level passed, now %1.").arg(training_level_text(*curriculum_, out.after.level));
  else
    text += ".";
  status_->setProperty("refusal", QString());
  status_->setStyleSheet("");
  status_->setText(text);
}

}  // namespace palprig::gui
