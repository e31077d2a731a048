#include "gui/localisation_marking.hpp"

#include <QHBoxLayout>
#include <QCoreApplication>
#include <QKeyEvent>
#include <QPushButton>
#include <QTimer>
#include <QVBoxLayout>

#include "gui/scene_view.hpp"
#include "study/localisation_case.hpp"

namespace palprig::gui {

LocalisationMarking::LocalisationMarking(QWidget* parent) : QWidget(parent) {
  setObjectName("localisation_marking");
  setFocusPolicy(Qt::StrongFocus);
  layout_ = new QVBoxLayout(this);
  auto* buttons = new QHBoxLayout;
  auto add = [&](const char* name, const char* text, void (LocalisationMarking::*slot)()) {
    auto* b = new QPushButton(text);
    b->setObjectName(name);
    b->setFocusPolicy(Qt::NoFocus);
    connect(b, &QPushButton::clicked, this, slot);
    buttons->addWidget(b);
  };
  add("undo_mark", "Undo (Backspace)", &LocalisationMarking::undo);
  add("clear_marks", "Clear", &LocalisationMarking::clear_marks);
  add("marks_done", "Done (Enter)", &LocalisationMarking::finish);
  layout_->addLayout(buttons);
  // The pen state is re-published on this heartbeat so a held pen does not age into a stale
  // input fault (gui/window_pen_input.hpp).
  heartbeat_ = new QTimer(this);
  heartbeat_->setInterval(16);
  connect(heartbeat_, &QTimer::timeout, this, [this] {
    if (view_) view_->heartbeat();
  });
}

LocalisationMarking::~LocalisationMarking() = default;

void LocalisationMarking::detach_pen() {
  heartbeat_->stop();
  if (view_) view_->set_pen_target(nullptr, PressureCurve{});
}

void LocalisationMarking::start_session(const Protocol& protocol, WindowPenInput* pen) {
  single_mark_ = false;
  pen_ = pen;
  case_key_.clear();
  if (!protocol.localisation.generate && !protocol.localisation.cases.empty())
    show_case(protocol.localisation.cases.front());
}

void LocalisationMarking::show_case(const LocalisationCase& c) {
  const std::string key = case_key(c);
  if (key == case_key_ && view_) return;
  show_scene(case_scene(c), pen_);
  case_key_ = key;
}

void LocalisationMarking::show_scene(SceneFile scene, WindowPenInput* pen) {
  delete view_;  // before the scene it points into is replaced
  view_ = nullptr;
  scene_ = std::move(scene);
  view_ = new SceneView(*scene_, FingerLayout{}, 100.0);
  view_->set_tumors_visible(false);
  view_->set_map_visible(false);
  view_->set_arteries_visible(false);
  if (pen) view_->set_pen_target(pen, PressureCurve{});
  connect(view_, &SceneView::markRequested, this, &LocalisationMarking::add_mark);
  layout_->insertWidget(0, view_, 1);
  marks_.clear();
  show_marks();
  heartbeat_->start();
}

void LocalisationMarking::add_mark(double x_mm, double y_mm) {
  if (!isEnabled()) return;
  if (single_mark_) marks_.clear();  // marking again moves the one mark
  marks_.push_back({x_mm, y_mm});
  show_marks();
}

void LocalisationMarking::undo() {
  if (!marks_.empty()) marks_.pop_back();
  show_marks();
}

void LocalisationMarking::clear_marks() {
  marks_.clear();
  show_marks();
}

void LocalisationMarking::finish() {
  if (isEnabled()) emit done();
}

void LocalisationMarking::show_marks() {
  if (!view_) return;
  std::vector<QPointF> mm;
  for (const Mark& m : marks_) mm.emplace_back(m.x_mm, m.y_mm);
  view_->set_marks(mm);
}

void LocalisationMarking::keyPressEvent(QKeyEvent* e) {
  if (e->key() == Qt::Key_Backspace) return undo();
  if (e->key() == Qt::Key_Return || e->key() == Qt::Key_Enter) return finish();
  if (e->key() == Qt::Key_M && view_) return mark_at_cursor();
  QWidget::keyPressEvent(e);
}

void LocalisationMarking::mark_at_cursor() {
  if (!view_) return;
  const QPoint at = view_->mapFromGlobal(QCursor::pos());
  QMouseEvent right(QEvent::MouseButtonPress, QPointF(at), view_->mapToGlobal(QPointF(at)), Qt::RightButton,
                    Qt::RightButton, Qt::NoModifier);
  QCoreApplication::sendEvent(view_, &right);
}

}  // namespace palprig::gui
