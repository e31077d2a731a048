#include "gui/rig_panel.hpp"

#include <QFrame>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>
#include <algorithm>

namespace palprig::gui {

RigPanel::RigPanel(LiveRun& run, QWidget* parent) : QWidget(parent), run_(run) {
  setObjectName("rig_panel");
  auto* col = new QVBoxLayout(this);
  auto* info = new QGridLayout;
  backend_ = new QLabel;
  link_ = new QLabel;
  state_ = new QLabel;
  state_->setObjectName("rig_state");
  input_ = new QLabel;
  input_->setWordWrap(true);
  // A tracker's input names its tools and wraps to four lines at the column's width; the grid
  // does not ask a wrapped label for its height, so the label would be cut to one line. Its
  // height follows its text (show_input): four lines for every input left the gauges' last line
  // (the rendering error) below the column's edge on a 1280 x 800 screen.
  input_->setMinimumHeight(4 * input_->fontMetrics().lineSpacing());
  info->addWidget(new QLabel("Rig"), 0, 0);
  info->addWidget(backend_, 0, 1);
  info->addWidget(new QLabel("Link"), 1, 0);
  info->addWidget(link_, 1, 1);
  info->addWidget(new QLabel("State"), 2, 0);
  info->addWidget(state_, 2, 1);
  info->addWidget(new QLabel("Input"), 3, 0);
  info->addWidget(input_, 3, 1);
  col->addLayout(info);

  auto* buttons = new QHBoxLayout;
  arm_ = new QPushButton("Arm");
  arm_->setObjectName("arm_button");
  disarm_ = new QPushButton("Disarm");
  vent_ = new QPushButton("VENT (Esc)");
  vent_->setObjectName("vent_button");
  vent_->setMinimumHeight(44);
  vent_->setStyleSheet("QPushButton { background: #c0161e; color: white; font-weight: bold; font-size: 15px; }");
  buttons->addWidget(arm_);
  buttons->addWidget(disarm_);
  col->addLayout(buttons);
  col->addWidget(vent_);

  banner_ = new QFrame;
  banner_->setObjectName("fault_banner");
  banner_->setStyleSheet("QFrame#fault_banner { background: #ffd9d9; border: 2px solid #c0161e; }");
  auto* b = new QHBoxLayout(banner_);
  banner_text_ = new QLabel;
  banner_text_->setObjectName("fault_text");
  banner_text_->setWordWrap(true);
  ack_ = new QPushButton("Acknowledge");
  ack_->setObjectName("acknowledge_button");
  b->addWidget(banner_text_, 1);
  b->addWidget(ack_);
  banner_->hide();
  col->addWidget(banner_);

  auto* gauges = new QHBoxLayout;
  for (int i = 0; i < kFingerCount; ++i) {
    gauges_[std::size_t(i)] = new FingerGauge(i);
    gauges->addWidget(gauges_[std::size_t(i)]);
  }
  col->addLayout(gauges, 1);

  connect(arm_, &QPushButton::clicked, this, [this] {
    run_.arm();
    update_controls();
  });
  connect(disarm_, &QPushButton::clicked, this, [this] {
    run_.disarm();
    update_controls();
  });
  connect(vent_, &QPushButton::clicked, this, &RigPanel::vent_now);
  connect(ack_, &QPushButton::clicked, this, [this] {
    run_.acknowledge_fault();
    banner_->hide();
    update_controls();
  });
}

void RigPanel::vent_now() {
  run_.vent();
  update_controls();
  emit vented();
}

void RigPanel::set_session_mode(bool on) {
  session_ = on;
  update_controls();
}

void RigPanel::update_controls() {
  if (session_) {
    state_->setText("study session: its pressures, live");
    state_->setStyleSheet("color: #0a4f9a; font-weight: bold;");
    arm_->setEnabled(false);
    disarm_->setEnabled(false);
    vent_->setEnabled(true);
    return;
  }
  const RigLifecycle s = run_.state();
  state_->setText(to_string(s));
  state_->setStyleSheet(s == RigLifecycle::armed   ? "color: #0a7a1e; font-weight: bold;"
                        : s == RigLifecycle::fault ? "color: #c0161e; font-weight: bold;"
                                                   : "font-weight: bold;");
  arm_->setEnabled(s == RigLifecycle::connected || s == RigLifecycle::vented);
  disarm_->setEnabled(s == RigLifecycle::armed);
  vent_->setEnabled(true);  // never disabled
}

void RigPanel::show_input(const QString& text) {
  if (text == input_->text()) return;
  input_->setText(text);
  // Lines the text wraps to in the value column (about 180 px wide in the 440 px column), two at
  // least (a trace's path wraps at its folder), four at most (a tracker's tools).
  const int text_px = input_->fontMetrics().horizontalAdvance(text);
  const int lines = std::clamp(text_px / 180 + 1, 2, 4);
  input_->setMinimumHeight(lines * input_->fontMetrics().lineSpacing());
}

void RigPanel::refresh(const FeedStatus& st) {
  backend_->setText(QString::fromStdString(run_.setup().rig.id + ": " + run_.backend_text()));
  link_->setText(session_ ? "the session's" : run_.linked() ? "up" : "DOWN (vented, reconnecting)");
  show_input(session_ ? "the session's pen or stimuli" : QString::fromStdString(run_.input_text()));
  update_controls();
  if (run_.fault_pending()) {
    banner_text_->setText("FAULT: " + QString::fromStdString(run_.fault_text()));
    banner_->show();
  }
  const double p_max = run_.setup().rig.safety.p_max_kPa;
  if (st.have_record)
    for (int i = 0; i < kFingerCount; ++i)
      gauges_[std::size_t(i)]->set_values(st.latest.target_kPa[i], st.latest.setpoint_kPa[i], st.latest.monitor_kPa[i],
                                          p_max, st.latest.t_s);
}

}  // namespace palprig::gui
