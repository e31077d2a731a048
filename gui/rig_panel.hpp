#pragma once
// RigPanel: what the rig is and what it does now: backend kind and link, lifecycle state with
// Arm / Disarm, the VENT button (always enabled; Esc anywhere in the window, see MainWindow),
// the three finger gauges, and the fault banner that stays until acknowledged.
#include <QWidget>
#include <array>

#include "gui/finger_gauge.hpp"
#include "gui/live_run.hpp"

class QLabel;
class QPushButton;
class QFrame;

namespace palprig::gui {

class RigPanel final : public QWidget {
  Q_OBJECT
 public:
  RigPanel(LiveRun& run, QWidget* parent = nullptr);
  void refresh(const FeedStatus& status);  // GUI poll
  QPushButton* vent_button() const noexcept { return vent_; }
  QPushButton* arm_button() const noexcept { return arm_; }
  QFrame* fault_banner() const noexcept { return banner_; }
  QLabel* fault_label() const noexcept { return banner_text_; }
  FingerGauge* gauge(int finger) const noexcept { return gauges_[std::size_t(finger)]; }
  // A study session owns the rig (the live loop is stopped): the gauges show the session's
  // ticks, Arm and Disarm are off, VENT stays (the window pauses the session with it).
  void set_session_mode(bool on);

 public slots:
  void vent_now();

 signals:
  void vented();

 private:
  void update_controls();                // state text and which buttons apply, at once after a click
  void show_input(const QString& text);  // the Input row, as tall as its text wraps

  LiveRun& run_;
  QLabel *backend_ = nullptr, *link_ = nullptr, *state_ = nullptr, *input_ = nullptr;
  QPushButton *arm_ = nullptr, *disarm_ = nullptr, *vent_ = nullptr, *ack_ = nullptr;
  QFrame* banner_ = nullptr;
  QLabel* banner_text_ = nullptr;
  std::array<FingerGauge*, kFingerCount> gauges_{};
  bool session_ = false;
};

}  // namespace palprig::gui
