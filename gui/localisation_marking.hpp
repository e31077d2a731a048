#pragma once
// LocalisationMarking: the participant's view of a tumor-localisation trial. The scene is drawn
// without its stiffness map or tumor outlines (gui/scene_view with both hidden); the left
// button (or the pen) palpates through the participant's WindowPenInput, which the session
// runs the trial with (Participant::pen()); the right button (the pen's side button) or M
// marks a suspected tumor where the pointer is. Undo, Clear and Done; Done hands the marks
// over, to be scored by experiments/scoring exactly as the CLI scores them.
// Pulse localisation uses the same screen (show_scene per trial, single_mark): the arteries are
// hidden as well, and there is one mark, where the pulse is strongest (marking again moves it),
// scored by models/pulse_localisation as the CLI scores it.
#include <QWidget>
#include <memory>
#include <optional>
#include <vector>

#include "study/protocol.hpp"
#include "study/scoring.hpp"
#include "formats/scene_file.hpp"
#include "gui/window_pen_input.hpp"

class QPushButton;
class QTimer;
class QVBoxLayout;

namespace palprig::gui {

class SceneView;

class LocalisationMarking final : public QWidget {
  Q_OBJECT
 public:
  explicit LocalisationMarking(QWidget* parent = nullptr);
  ~LocalisationMarking() override;

  // The pen to palpate with, and the protocol's first case when it has a fixed one (a protocol
  // that generates a case per trial shows each trial's with show_case).
  void start_session(const Protocol& protocol, WindowPenInput* pen);
  // The trial's case (study/localisation_case.hpp), made or loaded unless it is the one shown.
  void show_case(const LocalisationCase& c);
  // One scene to palpate (a pulse trial's): shown without map, tumor outlines or arteries; the
  // marks are cleared.
  void show_scene(SceneFile scene, WindowPenInput* pen);
  // true: at most one mark, a new one replaces it (pulse localisation).
  void set_single_mark(bool on) { single_mark_ = on; }
  SceneView* scene_view() const noexcept { return view_; }
  const std::vector<Mark>& marks() const noexcept { return marks_; }

  void add_mark(double x_mm, double y_mm);
  void undo();
  void mark_at_cursor();
  // The session that lent its pen is over: the heartbeat stops and the view lets go of the pen.
  // Must come before that session's ParticipantChannel (which owns the pen) may be released:
  // the 16 ms heartbeat wrote into a freed pen when a discrimination session followed a
  // localisation session in the same window (heap corruption, found by a user).
  void detach_pen();  // M: a mark where the pointer is (as a right-click there)
  void clear_marks();
  void finish();  // Done

 signals:
  void done();

 protected:
  void keyPressEvent(QKeyEvent*) override;

 private:
  void show_marks();

  std::optional<SceneFile> scene_;
  std::string case_key_;  // the case shown
  WindowPenInput* pen_ = nullptr;
  SceneView* view_ = nullptr;
  QVBoxLayout* layout_ = nullptr;
  QTimer* heartbeat_ = nullptr;
  std::vector<Mark> marks_;
  bool single_mark_ = false;
};

}  // namespace palprig::gui
