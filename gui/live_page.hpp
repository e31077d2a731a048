#pragma once
// LivePage: the live rig console, one page of the main window: scene view with the pen
// controls, rig panel, pulse controls and the live traces. poll() is its whole update: the
// main window's timer calls it every 16 ms.
#include <QWidget>
#include <vector>

#include "gui/live_run.hpp"
#include "gui/trace_history.hpp"

class QCheckBox;
class QDoubleSpinBox;
class QPushButton;
class QSlider;

namespace palprig::gui {

class RigPanel;
class SceneView;
class StripChart;
class TrackerPanel;

class LivePage final : public QWidget {
  Q_OBJECT
 public:
  // `reveal_answer`: the tumors shown (outlines and stiffness colours) from the start, as for the
  // bundled demo phantom; otherwise (a rehearsal case opened with --scene or from the File menu)
  // the trainee's view is plain tissue until the trainer reveals it (Ctrl+T) for the debriefing.
  LivePage(LiveRun& run, bool reveal_answer, QWidget* parent = nullptr);
  FeedStatus poll();  // take new telemetry, refresh every panel; returns the feed's status

  RigPanel* rig_panel() const noexcept { return rig_panel_; }
  SceneView* scene_view() const noexcept { return scene_view_; }
  StripChart* strip_chart() const noexcept { return chart_; }
  TrackerPanel* tracker_panel() const noexcept { return tracker_; }  // null unless the input is a tracker
  // "Show the tumors (Ctrl+T)": outlines and stiffness colours together.
  QCheckBox* tumor_outlines() const noexcept { return tumors_; }
  const TraceHistory& history() const noexcept { return history_; }
  void toggle_pause();
  void clear_traces();
  // A study session owns the rig: the page shows the session's ticks (the feed receives them,
  // sessions' tick_observer) and takes no pen input; the rig panel says so.
  void set_session_owns_rig(bool on);

 private:
  LiveRun& run_;
  TraceHistory history_;
  std::vector<TraceSample> incoming_;
  RigPanel* rig_panel_ = nullptr;
  SceneView* scene_view_ = nullptr;
  StripChart* chart_ = nullptr;
  TrackerPanel* tracker_ = nullptr;
  QCheckBox* tumors_ = nullptr;
  QSlider* force_ = nullptr;
  QPushButton* pause_ = nullptr;
  QDoubleSpinBox* window_ = nullptr;
};

}  // namespace palprig::gui
