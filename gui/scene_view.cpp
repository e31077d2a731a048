#include "gui/scene_view.hpp"

#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QTabletEvent>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include "gui/scene_image.hpp"
#include "models/tissue_scene.hpp"
#include "runtime/monotonic_clock.hpp"

namespace palprig::gui {

namespace {
constexpr double kFingerRadius_mm = 8.0;  // a 16 mm fingertip (paper 002)
constexpr int kImageMaxPx = 480;
// A function scene costs about 5 us per sample (every layer and inclusion is evaluated), so it
// is rendered coarser and scaled up: 200 px is about 0.2 s of one core, done once, and a
// breathing scene's 120 px re-render (about 70 ms) runs on a worker thread once a second.
constexpr int kFunctionImageMaxPx = 200, kBreathingImageMaxPx = 120;
constexpr double kRenderForce_N = 2.0;  // the scene as the reference press feels it
}  // namespace

SceneView::SceneView(const SceneFile& scene, const FingerLayout& layout, double p_max_kPa, QWidget* parent)
    : QWidget(parent),
      scene_(scene.scene.get()),
      bounds_(scene.scene->bounds()),
      tumors_(scene.tumors),
      layout_(layout),
      p_max_kPa_(p_max_kPa) {
  setObjectName("scene_view");
  setMinimumSize(320, 240);
  setMouseTracking(false);
  setAttribute(Qt::WA_TabletTracking);
  if (const auto* f = dynamic_cast<const FunctionScene*>(scene_)) {
    breathing_ = f->field().definition().respiration.breathing();
    for (std::size_t i = 0; i < f->arteries().size(); ++i) {
      arteries_.push_back(f->arteries().artery(i).spec().path);
      artery_names_.push_back(f->arteries().artery(i).spec().name);
    }
  }
  const int px = dynamic_cast<const FunctionScene*>(scene_) ? kFunctionImageMaxPx : kImageMaxPx;
  image_ = render_scene_image(*scene_, kRenderForce_N, 0.0, px, px);
}

SceneView::~SceneView() {
  if (pending_image_.valid()) pending_image_.wait();
}

void SceneView::set_pen_target(WindowPenInput* pen, const PressureCurve& curve) {
  pen_input_ = pen;
  curve_ = curve;
}

void SceneView::set_mouse_force_N(double f) {
  mouse_force_N_ = std::clamp(f, 0.0, 10.0);
  if (pen_.in_contact) pen_.force_N = mouse_force_N_;
}

void SceneView::set_map_visible(bool on) {
  map_visible_ = on;
  update();
}

void SceneView::set_marks(const std::vector<QPointF>& marks_mm) {
  marks_mm_ = marks_mm;
  update();
}

void SceneView::set_arteries_visible(bool on) {
  arteries_visible_ = on;
  update();
}

void SceneView::set_tumors_visible(bool on) {
  tumors_visible_ = on;
  update();
}

QRectF SceneView::scene_rect() const {
  const double w_mm = bounds_.x1_mm - bounds_.x0_mm, h_mm = bounds_.y1_mm - bounds_.y0_mm;
  const double margin = 8;
  const double s = std::min((width() - 2 * margin) / w_mm, (height() - 2 * margin) / h_mm);
  const double w = w_mm * s, h = h_mm * s;
  return {(width() - w) / 2, (height() - h) / 2, w, h};
}

QPointF SceneView::pixel_of(double x_mm, double y_mm) const {
  const QRectF r = scene_rect();
  return {r.left() + (x_mm - bounds_.x0_mm) / (bounds_.x1_mm - bounds_.x0_mm) * r.width(),
          r.top() + (y_mm - bounds_.y0_mm) / (bounds_.y1_mm - bounds_.y0_mm) * r.height()};
}

QPointF SceneView::mm_of(const QPointF& px) const {
  const QRectF r = scene_rect();
  return {bounds_.x0_mm + (px.x() - r.left()) / r.width() * (bounds_.x1_mm - bounds_.x0_mm),
          bounds_.y0_mm + (px.y() - r.top()) / r.height() * (bounds_.y1_mm - bounds_.y0_mm)};
}

void SceneView::publish_pen(const QPointF& pixel, double force_N, bool in_contact) {
  const QPointF mm = mm_of(pixel);
  pen_ = WindowPen{mm.x(), mm.y(), force_N, in_contact, mono_ns()};
  if (pen_input_) pen_input_->publish(pen_);
}

void SceneView::heartbeat() {
  if (!pen_input_) return;
  pen_.stamp_ns = mono_ns();
  pen_input_->publish(pen_);
}

void SceneView::mousePressEvent(QMouseEvent* e) {
  if (e->button() == Qt::RightButton) {
    const QPointF mm = mm_of(e->position());
    emit markRequested(mm.x(), mm.y());
    return;
  }
  if (e->button() != Qt::LeftButton) return;
  publish_pen(e->position(), mouse_force_N_, true);
}

void SceneView::mouseMoveEvent(QMouseEvent* e) {
  if (!(e->buttons() & Qt::LeftButton)) return;
  publish_pen(e->position(), mouse_force_N_, true);
}

void SceneView::mouseReleaseEvent(QMouseEvent* e) {
  if (e->button() != Qt::LeftButton) return;
  publish_pen(e->position(), 0.0, false);
}

void SceneView::wheelEvent(QWheelEvent* e) {
  // One wheel notch (120) is 0.1 N.
  set_mouse_force_N(mouse_force_N_ + 0.1 * e->angleDelta().y() / 120.0);
  if (pen_.in_contact && pen_input_) heartbeat();
  emit mouseForceChanged(mouse_force_N_);
  e->accept();
}

void SceneView::tabletEvent(QTabletEvent* e) {
  // The pen's normalised pressure through the rig's pressure curve, as the evdev tablet input
  // does; accepting the event stops Qt from also sending it as a mouse event.
  const double force = curve_.force_N(std::clamp(double(e->pressure()), 0.0, 1.0));
  switch (e->type()) {
    case QEvent::TabletPress:
    case QEvent::TabletMove: publish_pen(e->position(), force, e->pressure() > 0); break;
    case QEvent::TabletRelease: publish_pen(e->position(), 0.0, false); break;
    default: break;
  }
  e->accept();
}

void SceneView::resizeEvent(QResizeEvent*) { update(); }

void SceneView::show_record(const TelemetryRecord& r) {
  record_ = r;
  have_record_ = true;
  update();
}

void SceneView::advance_scene_time(double t_s) {
  if (!breathing_) return;
  if (pending_image_.valid() && pending_image_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    image_ = pending_image_.get();
    update();
  }
  if (!pending_image_.valid() && std::abs(t_s - last_render_t_s_) >= 1.0) {
    last_render_t_s_ = t_s;
    const Scene* scene = scene_;
    pending_image_ = std::async(std::launch::async, [scene, t_s] {
      return render_scene_image(*scene, kRenderForce_N, t_s, kBreathingImageMaxPx, kBreathingImageMaxPx);
    });
  }
}

std::array<Point2_mm, kFingerCount> SceneView::finger_centres() const {
  // Tracked fingers each stand where their tool is (the record says where); the pen's three
  // stand in the layout's triangle around it.
  if (!(record_.flags & kOwnPositions)) return layout_.centres(record_.x_mm, record_.y_mm);
  std::array<Point2_mm, kFingerCount> c{};
  for (int i = 0; i < kFingerCount; ++i) c[i] = {record_.finger_x_mm[i], record_.finger_y_mm[i]};
  return c;
}

std::array<QPointF, kFingerCount> SceneView::finger_pixels() const {
  std::array<QPointF, kFingerCount> out{};
  const auto c = finger_centres();
  for (int i = 0; i < kFingerCount; ++i) out[i] = pixel_of(c[i].x_mm, c[i].y_mm);
  return out;
}

std::array<QColor, kFingerCount> SceneView::finger_colours() const {
  std::array<QColor, kFingerCount> out{};
  for (int i = 0; i < kFingerCount; ++i) out[i] = pressure_colour(record_.setpoint_kPa[i], p_max_kPa_);
  return out;
}

void SceneView::draw_indentation(QPainter& p, const Point2_mm& c, double depth_mm, double drag_x_mm, double drag_y_mm) {
  const int n = 4;
  // The sub-grid spans two finger widths, and more when the tissue is dragged further (so the
  // stretched skin reaches undeformed tissue at its border).
  const double drag = std::isfinite(drag_x_mm) && std::isfinite(drag_y_mm) ? std::hypot(drag_x_mm, drag_y_mm) : 0.0;
  const double cell = std::max(2.0 * kFingerRadius_mm, kFingerRadius_mm + 1.5 * drag) / n;
  const auto grid = tiered_grid(c.x_mm, c.y_mm, depth_mm, n, cell, drag_x_mm, drag_y_mm);
  const std::size_t side = 2 * n + 1;
  // A sunk vertex is drawn pulled toward the contact (the surface stretches into the dimple),
  // a quarter of its depth, and the cells darken with depth.
  std::vector<QPointF> px(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    // Where the (dragged) vertex is, then pulled toward the contact by the dimple.
    const double x = grid[i].x_mm + grid[i].dx_mm, y = grid[i].y_mm + grid[i].dy_mm;
    const double dx = x - c.x_mm, dy = y - c.y_mm;
    const double r = std::hypot(dx, dy);
    const double pull = r > 0 ? std::min(0.25 * grid[i].depth_mm, r * 0.5) / r : 0.0;
    px[i] = pixel_of(x - dx * pull, y - dy * pull);
  }
  for (std::size_t r = 0; r + 1 < side; ++r)
    for (std::size_t col = 0; col + 1 < side; ++col) {
      const std::size_t a = r * side + col;
      const double d =
          (grid[a].depth_mm + grid[a + 1].depth_mm + grid[a + side].depth_mm + grid[a + side + 1].depth_mm) / 4;
      QPolygonF quad({px[a], px[a + 1], px[a + side + 1], px[a + side]});
      p.setPen(QPen(QColor(70, 40, 40, 140), 0.8));
      p.setBrush(QColor(30, 10, 10, int(std::clamp(d / indentation_.max_depth_mm, 0.0, 1.0) * 150)));
      p.drawPolygon(quad);
    }
}

void SceneView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  render_to(p);
}

void SceneView::render_to(QPainter& p) {
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), QColor(60, 60, 66));
  const QRectF r = scene_rect();
  if (map_visible_)
    p.drawImage(r, image_);
  else
    p.fillRect(r, QColor(222, 184, 160));  // plain tissue: nothing to see, only to feel
  p.save();
  p.setClipRect(r);  // the tissue, its arteries and dimples end at the scene's edge
  const double px_per_mm = r.width() / (bounds_.x1_mm - bounds_.x0_mm);
  // A light 10 mm grid: the undeformed surface the dimples sink into.
  p.setPen(QPen(QColor(255, 255, 255, 60), 1));
  for (double x = bounds_.x0_mm + 10; x < bounds_.x1_mm; x += 10)
    p.drawLine(pixel_of(x, bounds_.y0_mm), pixel_of(x, bounds_.y1_mm));
  for (double y = bounds_.y0_mm + 10; y < bounds_.y1_mm; y += 10)
    p.drawLine(pixel_of(bounds_.x0_mm, y), pixel_of(bounds_.x1_mm, y));
  // Arteries.
  for (std::size_t a = 0; arteries_visible_ && a < arteries_.size(); ++a) {
    QPainterPath path;
    for (std::size_t i = 0; i < arteries_[a].size(); ++i) {
      const QPointF q = pixel_of(arteries_[a][i].x_mm, arteries_[a][i].y_mm);
      if (i == 0)
        path.moveTo(q);
      else
        path.lineTo(q);
    }
    p.setPen(QPen(QColor(170, 0, 30, 200), std::max(2.0, 2.0 * px_per_mm), Qt::SolidLine, Qt::RoundCap));
    p.setBrush(Qt::NoBrush);
    p.drawPath(path);
    if (!arteries_[a].empty()) {
      p.setPen(Qt::white);
      p.drawText(pixel_of(arteries_[a][0].x_mm, arteries_[a][0].y_mm) + QPointF(4, -4),
                 QString::fromStdString(artery_names_[a]));
    }
  }
  // Tumor outlines (experimenter only).
  if (tumors_visible_) {
    for (const TumorTruth& t : tumors_) {
      const QPointF c = pixel_of(t.x_mm, t.y_mm);
      const double rad = t.radius_mm * px_per_mm;
      p.setPen(QPen(QColor(255, 255, 255), 1.5, Qt::DashLine));
      p.setBrush(Qt::NoBrush);
      p.drawEllipse(c, rad, rad);
      p.drawText(c + QPointF(rad + 3, -rad), QString::fromStdString(t.name));
    }
  }
  // The participant's marks, numbered in the order placed.
  for (std::size_t i = 0; i < marks_mm_.size(); ++i) {
    const QPointF c = pixel_of(marks_mm_[i].x(), marks_mm_[i].y());
    p.setPen(QPen(QColor(0, 90, 200), 3));
    p.drawLine(c + QPointF(-8, -8), c + QPointF(8, 8));
    p.drawLine(c + QPointF(-8, 8), c + QPointF(8, -8));
    p.drawText(c + QPointF(10, -6), QString::number(i + 1));
  }
  if (!have_record_) {
    p.restore();
    return;
  }
  const bool pressed = record_.flags & kInContact;
  const auto centres = finger_centres();
  // A tracked finger whose tool is out of view is vented: drawn hollow and dashed where its tool
  // was last seen, with why; one never seen is not drawn.
  auto vented = [this](int i) { return record_.finger_vent[i] != FingerVent::none; };
  if (pressed)
    for (int i = 0; i < kFingerCount; ++i)
      if (!vented(i))
        draw_indentation(p, centres[i], indentation_.depth_mm(record_.finger_force_N[i], record_.stiffness[i]),
                         record_.drag_x_mm[i], record_.drag_y_mm[i]);
  p.restore();
  for (int i = 0; i < kFingerCount; ++i) {
    const QPointF c = pixel_of(centres[i].x_mm, centres[i].y_mm);
    const double rad = kFingerRadius_mm * px_per_mm;
    if (vented(i)) {
      // A tool never seen (or no tool at all) has no place to be drawn.
      if (record_.finger_vent[i] == FingerVent::no_tool || record_.finger_vent[i] == FingerVent::tool_not_seen)
        continue;
      p.setBrush(Qt::NoBrush);
      p.setPen(QPen(QColor(230, 230, 230), 1.5, Qt::DashLine));
      p.drawEllipse(c, rad, rad);
      p.setPen(Qt::white);
      p.drawText(QRectF(c.x() - 10, c.y() - 8, 20, 16), Qt::AlignCenter, QString::number(i + 1));
      p.drawText(c + QPointF(rad + 2, 4), record_.finger_vent[i] == FingerVent::tool_stale ? "out of view" : "vented");
      continue;
    }
    QColor fill = pressure_colour(record_.setpoint_kPa[i], p_max_kPa_);
    fill.setAlpha(pressed ? 170 : 70);
    p.setBrush(fill);
    p.setPen(QPen(pressed ? Qt::black : QColor(230, 230, 230), pressed ? 2.0 : 1.0));
    p.drawEllipse(c, rad, rad);
    p.setPen(Qt::black);
    p.drawText(QRectF(c.x() - 10, c.y() - 8, 20, 16), Qt::AlignCenter, QString::number(i + 1));
  }
  if (record_.flags & kOwnPositions) return;  // no pen: each finger is its own
  // The pen: a cross-hair at finger 1's vertex, with the force.
  const QPointF pen = pixel_of(record_.x_mm, record_.y_mm);
  p.setPen(QPen(Qt::white, 1.5));
  p.drawLine(pen + QPointF(-6, 0), pen + QPointF(6, 0));
  p.drawLine(pen + QPointF(0, -6), pen + QPointF(0, 6));
  p.drawText(pen + QPointF(8, 16), QString("%1 N").arg(record_.force_N, 0, 'f', 2));
}

}  // namespace palprig::gui
