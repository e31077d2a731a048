#pragma once
// PulsePanel: for scenes with arteries, each artery's rate (BPM) and amplitude (kPa) changed
// while the loop runs (PulseField's request_rate_bpm / request_amplitude_kPa: relaxed atomics
// the loop reads at its next tick, phase kept continuous), and the regulator-lag compensation
// switch (PulseRendering::compensate_lag_switch).
#include <QGroupBox>

#include "gui/live_run.hpp"

namespace palprig::gui {

class PulsePanel final : public QGroupBox {
  Q_OBJECT
 public:
  PulsePanel(LiveRun& run, QWidget* parent = nullptr);
};

}  // namespace palprig::gui
