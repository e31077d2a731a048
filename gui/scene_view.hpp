#pragma once
// SceneView: the tissue, the pen and the three fingers, and the pen input itself.
//
// Shows the scene (stiffness map or rendered function scene; breathing scenes are re-rendered
// once a second on a worker thread), arteries, tumor outlines (hidden for participants), the
// pen position from the loop's telemetry, the three finger circles coloured by the setpoint each
// finger gets, and the tissue indenting under each pressing finger (paper 001's tiered grid,
// gui/indentation.hpp).
//
// Input: mouse (left button presses; the force is the slider's or the wheel's) and tablet pens
// (QTabletEvent position and pressure; the pressure curve is the rig file's tablet section)
// become WindowPen states published to the loop (gui/window_pen_input.hpp). heartbeat()
// re-publishes the current state on the GUI's poll timer.
#include <QImage>
#include <QWidget>
#include <array>
#include <future>
#include <vector>

#include "controller/telemetry.hpp"
#include "formats/scene_file.hpp"
#include "formats/tablet_config.hpp"
#include "gui/indentation.hpp"
#include "gui/window_pen_input.hpp"
#include "models/finger_layout.hpp"

namespace palprig::gui {

class SceneView final : public QWidget {
  Q_OBJECT
 public:
  SceneView(const SceneFile& scene, const FingerLayout& layout, double p_max_kPa, QWidget* parent = nullptr);
  ~SceneView() override;

  void set_pen_target(WindowPenInput* pen, const PressureCurve& curve);  // null: the input is not the window
  void set_mouse_force_N(double f);
  double mouse_force_N() const noexcept { return mouse_force_N_; }
  void set_tumors_visible(bool on);
  bool tumors_visible() const noexcept { return tumors_visible_; }
  // The participant's view: the stiffness map hidden too (it would show the tumors), and the
  // marks placed so far (x, y in mm; drawn numbered). Right-click asks for a mark there.
  void set_map_visible(bool on);
  bool map_visible() const noexcept { return map_visible_; }
  void set_marks(const std::vector<QPointF>& marks_mm);
  // The pulse-localisation participant's view hides the arteries (and their names) too.
  void set_arteries_visible(bool on);
  bool arteries_visible() const noexcept { return arteries_visible_; }
  void heartbeat();                            // GUI poll: re-publish the pen state
  void show_record(const TelemetryRecord& r);  // what the loop did last
  void advance_scene_time(double t_s);         // breathing scenes: re-render now and then

  // Where the fingers are drawn (widget pixels) and their fill colours, for tests.
  std::array<QPointF, kFingerCount> finger_pixels() const;
  // Where the fingers are on the scene: the record's own positions (tracked fingers) or the
  // layout's triangle around the pen.
  std::array<Point2_mm, kFingerCount> finger_centres() const;
  std::array<QColor, kFingerCount> finger_colours() const;
  QPointF pixel_of(double x_mm, double y_mm) const;
  bool pen_down() const noexcept { return pen_.in_contact; }
  double shown_force_N() const noexcept { return record_.force_N; }  // the loop's, as drawn
  void render_to(QPainter& p);                                       // the whole view into any painter (benchmarks)

 signals:
  void mouseForceChanged(double force_N);
  void markRequested(double x_mm, double y_mm);  // right button (the pen's side button)

 protected:
  void paintEvent(QPaintEvent*) override;
  void mousePressEvent(QMouseEvent*) override;
  void mouseMoveEvent(QMouseEvent*) override;
  void mouseReleaseEvent(QMouseEvent*) override;
  void wheelEvent(QWheelEvent*) override;
  void tabletEvent(QTabletEvent*) override;
  void resizeEvent(QResizeEvent*) override;

 private:
  QRectF scene_rect() const;  // where the scene's bounds are drawn
  QPointF mm_of(const QPointF& pixel) const;
  void publish_pen(const QPointF& pixel, double force_N, bool in_contact);
  void draw_indentation(QPainter& p, const Point2_mm& c, double depth_mm, double drag_x_mm, double drag_y_mm);

  const Scene* scene_;
  SceneBounds bounds_;
  std::vector<TumorTruth> tumors_;
  std::vector<std::vector<Point2_mm>> arteries_;
  std::vector<std::string> artery_names_;
  FingerLayout layout_;
  double p_max_kPa_;
  bool breathing_ = false;
  QImage image_;
  std::future<QImage> pending_image_;
  double last_render_t_s_ = 0;

  WindowPenInput* pen_input_ = nullptr;
  PressureCurve curve_;
  WindowPen pen_;
  double mouse_force_N_ = 2.0;
  bool tumors_visible_ = true;
  bool map_visible_ = true;
  bool arteries_visible_ = true;
  std::vector<QPointF> marks_mm_;
  bool have_record_ = false;
  TelemetryRecord record_;
  IndentationModel indentation_;
};

}  // namespace palprig::gui
