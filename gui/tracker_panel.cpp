#include "gui/tracker_panel.hpp"

#include <QGridLayout>
#include <QLabel>

#include "runtime/monotonic_clock.hpp"

namespace palprig::gui {

TrackerPanel::TrackerPanel(LiveRun& run, QWidget* parent) : QGroupBox("Tracker", parent), run_(run) {
  setObjectName("tracker_panel");
  auto* grid = new QGridLayout(this);
  connection_ = new QLabel;
  connection_->setObjectName("tracker_connection");
  connection_->setWordWrap(true);
  grid->addWidget(connection_, 0, 0, 1, 2);
  const TrackingConfig* t = run.tracking();
  const int n = t ? int(t->tools.size()) : 0;
  for (int k = 0; k < n; ++k) {
    const TrackedTool& tool = t->tools[std::size_t(k)];
    const QString finger = t->placement == TrackedPlacement::per_finger ? QString("finger %1").arg(tool.finger + 1)
                                                                        : QString("fingers 1-3 (triangle)");
    grid->addWidget(new QLabel(QString::fromStdString(tool.name) + " -> " + finger), k + 1, 0);
    auto* state = new QLabel("-");
    state->setObjectName(QString("tracker_tool_%1").arg(k));
    grid->addWidget(state, k + 1, 1);
    tools_.push_back(state);
  }
  others_ = new QLabel;
  others_->setObjectName("tracker_other_devices");
  others_->setWordWrap(true);
  grid->addWidget(others_, n + 1, 0, 1, 2);
  refresh();
}

void TrackerPanel::refresh() {
  const std::optional<TrackerStatus> st = run_.tracker_status();
  if (!st) return;
  const std::int64_t now = mono_ns();
  const double stale_s = run_.setup().rig.safety.max_input_age_s;
  connection_->setText(QString("%1: %2, %3 messages%4")
                           .arg(QString::fromStdString(run_.input_text()))
                           .arg(st->connected ? "connected" : "<b>connection lost</b>")
                           .arg(st->messages)
                           .arg(st->skipped ? QString(" (%1 skipped)").arg(st->skipped) : QString()));
  for (std::size_t k = 0; k < tools_.size(); ++k) {
    const TrackedToolState& ts = st->tools[k];
    QString text;
    bool bad = true;
    if (ts.refused != FingerVent::none)
      text = QString::fromUtf8(to_string(ts.refused));
    else if (ts.arrived_ns == 0)
      text = "not seen: vented";
    else {
      const double age_s = double(now - ts.arrived_ns) * 1e-9;
      bad = age_s > stale_s;
      text = QString("%1 poses, last %2 ms ago%3")
                 .arg(ts.poses)
                 .arg(age_s * 1000, 0, 'f', 0)
                 .arg(bad ? ": out of view, vented" : "");
    }
    tools_[k]->setText(text);
    tools_[k]->setStyleSheet(bad ? "color: #c00000" : "");
  }
  QString others;
  for (const auto& name : st->other_names)
    if (name[0]) others += (others.isEmpty() ? "" : ", ") + QString::fromLatin1(name);
  others_->setText(others.isEmpty() ? QString() : "also sent (not mapped): " + others);
}

}  // namespace palprig::gui
