#include "gui/live_page.hpp"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QSlider>
#include <QSplitter>
#include <QVBoxLayout>
#include <cmath>

#include "gui/pulse_panel.hpp"
#include "gui/rig_panel.hpp"
#include "gui/scene_view.hpp"
#include "gui/strip_chart.hpp"
#include "gui/tracker_panel.hpp"

namespace palprig::gui {

LivePage::LivePage(LiveRun& run, bool reveal_answer, QWidget* parent)
    // 60 s (the longest window) at the loop's rate.
    : QWidget(parent), run_(run), history_(std::size_t(std::lround(60.0 * 1000.0)) + 1000) {
  auto* outer = new QVBoxLayout(this);
  auto* split = new QSplitter(Qt::Vertical);
  outer->addWidget(split);

  auto* top = new QWidget;
  auto* top_row = new QHBoxLayout(top);
  top_row->setContentsMargins(0, 0, 0, 0);

  // Left: the scene and the pen's controls.
  auto* left = new QWidget;
  auto* left_col = new QVBoxLayout(left);
  left_col->setContentsMargins(0, 0, 0, 0);
  scene_view_ = new SceneView(run.setup().scene, run.setup().config.layout, run.setup().rig.safety.p_max_kPa);
  scene_view_->set_pen_target(run.window_pen(), run.setup().rig.tablet.pressure);
  left_col->addWidget(scene_view_, 1);
  auto* pen_row = new QHBoxLayout;
  pen_row->addWidget(new QLabel("Mouse force"));
  force_ = new QSlider(Qt::Horizontal);
  force_->setObjectName("force_slider");
  force_->setRange(0, 60);  // tenths of a newton
  force_->setValue(int(std::lround(scene_view_->mouse_force_N() * 10)));
  auto* force_text = new QLabel(QString("%1 N").arg(scene_view_->mouse_force_N(), 0, 'f', 1));
  pen_row->addWidget(force_, 1);
  pen_row->addWidget(force_text);
  // The answer: tumor outlines and the stiffness colours (which show the tumors as plainly).
  tumors_ = new QCheckBox("Show the tumors (Ctrl+T)");
  tumors_->setObjectName("tumor_outlines");
  tumors_->setToolTip("Tumor outlines and stiffness colours; a trainee palpates plain tissue");
  tumors_->setChecked(reveal_answer);
  scene_view_->set_tumors_visible(reveal_answer);
  scene_view_->set_map_visible(reveal_answer);
  pen_row->addWidget(tumors_);
  left_col->addLayout(pen_row);
  if (!run.window_pen())
    left_col->addWidget(
        new QLabel("Pen input: " + QString::fromStdString(run.input_text()) + " (the window pen is off)"));
  connect(force_, &QSlider::valueChanged, this, [this, force_text](int v) {
    scene_view_->set_mouse_force_N(v / 10.0);
    force_text->setText(QString("%1 N").arg(v / 10.0, 0, 'f', 1));
  });
  connect(scene_view_, &SceneView::mouseForceChanged, this,
          [this](double f) { force_->setValue(int(std::lround(f * 10))); });
  connect(tumors_, &QCheckBox::toggled, scene_view_, [this](bool on) {
    scene_view_->set_tumors_visible(on);
    scene_view_->set_map_visible(on);
  });

  // Right: the rig and the pulse.
  auto* right = new QWidget;
  auto* right_col = new QVBoxLayout(right);
  right_col->setContentsMargins(0, 0, 0, 0);
  rig_panel_ = new RigPanel(run);
  right_col->addWidget(rig_panel_, 1);
  if (run.tracker_status()) {
    tracker_ = new TrackerPanel(run);
    right_col->addWidget(tracker_);
  }
  right_col->addWidget(new PulsePanel(run));
  // With the tracker's panel the column is taller than a 1280 x 800 screen leaves it: it scrolls
  // instead of growing the window past the screen (its widgets keep their minimum heights).
  auto* right_scroll = new QScrollArea;
  right_scroll->setObjectName("liveRightColumn");
  right_scroll->setWidgetResizable(true);
  right_scroll->setFrameShape(QFrame::NoFrame);
  right_scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  right_scroll->setWidget(right);
  right_scroll->setMaximumWidth(440);
  top_row->addWidget(left, 3);
  top_row->addWidget(right_scroll, 2);
  split->addWidget(top);

  // Bottom: the traces.
  auto* traces = new QWidget;
  auto* traces_col = new QVBoxLayout(traces);
  traces_col->setContentsMargins(0, 0, 0, 0);
  chart_ = new StripChart(&history_);
  chart_->set_p_max_kPa(run.setup().rig.safety.p_max_kPa);
  traces_col->addWidget(chart_, 1);
  auto* trace_row = new QHBoxLayout;
  pause_ = new QPushButton("Pause (Space)");
  pause_->setObjectName("pause_button");
  pause_->setCheckable(true);
  auto* clear = new QPushButton("Clear");
  window_ = new QDoubleSpinBox;
  window_->setObjectName("window_s");
  window_->setRange(2, 60);
  window_->setDecimals(0);
  window_->setValue(10);
  window_->setSuffix(" s");
  trace_row->addWidget(pause_);
  trace_row->addWidget(clear);
  trace_row->addWidget(new QLabel("Window"));
  trace_row->addWidget(window_);
  trace_row->addStretch(1);
  traces_col->addLayout(trace_row);
  split->addWidget(traces);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 2);
  connect(pause_, &QPushButton::toggled, chart_, &StripChart::set_paused);
  connect(clear, &QPushButton::clicked, this, &LivePage::clear_traces);
  connect(window_, &QDoubleSpinBox::valueChanged, chart_, &StripChart::set_window_s);
}

void LivePage::toggle_pause() { pause_->toggle(); }

void LivePage::set_session_owns_rig(bool on) {
  scene_view_->setEnabled(!on);
  if (force_) force_->setEnabled(!on);
  rig_panel_->set_session_mode(on);
  if (on) clear_traces();  // the session's clock starts at 0
}

void LivePage::clear_traces() {
  history_.clear();
  chart_->update();
}

FeedStatus LivePage::poll() {
  scene_view_->heartbeat();
  incoming_.clear();
  const FeedStatus st = run_.feed().take(incoming_);
  for (const TraceSample& s : incoming_) {
    // A new run (after a fault) starts its clock at 0: the old run's traces are history.
    if (history_.size() && s.t_s < history_.newest().t_s) history_.clear();
    history_.push(s);
  }
  if (st.have_record) {
    scene_view_->show_record(st.latest);
    scene_view_->advance_scene_time(st.latest.t_s);
  }
  rig_panel_->refresh(st);
  if (tracker_) tracker_->refresh();
  if (!chart_->paused() && !incoming_.empty()) chart_->update();
  return st;
}

}  // namespace palprig::gui
