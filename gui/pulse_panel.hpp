#pragma once
// PulsePanel: for scenes with arteries, each artery's rate (BPM) and amplitude (kPa) changed
// while the loop runs, and the regulator-lag compensation switch: LiveRun::switches()
// (controller/operator_switches.hpp), which the loop reads into the tick's inputs every tick (a
// rate applies from the next tick, phase kept continuous).
#include <QGroupBox>

#include "gui/live_run.hpp"

namespace palprig::gui {

class PulsePanel final : public QGroupBox {
  Q_OBJECT
 public:
  PulsePanel(LiveRun& run, QWidget* parent = nullptr);
};

}  // namespace palprig::gui
