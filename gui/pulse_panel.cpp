#include "gui/pulse_panel.hpp"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QLabel>

#include "models/artery.hpp"
#include "models/pulse_waveform.hpp"

namespace palprig::gui {

PulsePanel::PulsePanel(LiveRun& run, QWidget* parent) : QGroupBox("Pulse", parent) {
  setObjectName("pulse_panel");
  auto* grid = new QGridLayout(this);
  const PulseField* field = run.scene().pulse();
  if (!field || field->empty()) {
    grid->addWidget(new QLabel("This scene has no arteries."), 0, 0);
    return;
  }
  grid->addWidget(new QLabel("artery"), 0, 0);
  grid->addWidget(new QLabel("rate BPM"), 0, 1);
  grid->addWidget(new QLabel("amplitude kPa"), 0, 2);
  for (std::size_t i = 0; i < field->size(); ++i) {
    const int row = int(i) + 1;
    grid->addWidget(new QLabel(QString::fromStdString(field->artery(i).spec().name)), row, 0);
    auto* bpm = new QDoubleSpinBox;
    bpm->setObjectName(QString("bpm_%1").arg(i));
    bpm->setRange(kMinPulseRateBpm, kMaxPulseRateBpm);
    bpm->setDecimals(0);
    bpm->setValue(field->rate_bpm(i, run.switches().read().pulse));
    auto* amp = new QDoubleSpinBox;
    amp->setObjectName(QString("amplitude_%1").arg(i));
    amp->setRange(0, kMaxPulseAmplitude_kPa);
    amp->setSingleStep(0.5);
    amp->setDecimals(1);
    amp->setValue(field->amplitude_kPa(i, run.switches().read().pulse));
    grid->addWidget(bpm, row, 1);
    grid->addWidget(amp, row, 2);
    OperatorSwitches* switches = &run.switches();
    connect(bpm, &QDoubleSpinBox::valueChanged, this,
            [switches, i](double v) { switches->request_pulse_rate_bpm(i, v); });
    connect(amp, &QDoubleSpinBox::valueChanged, this,
            [switches, i](double v) { switches->request_pulse_amplitude_kPa(i, v); });
  }
  auto* lag = new QCheckBox("Regulator lag compensation");
  lag->setObjectName("lag_compensation");
  lag->setChecked(run.lag_compensation());
  connect(lag, &QCheckBox::toggled, this, [&run](bool on) { run.set_lag_compensation(on); });
  grid->addWidget(lag, int(field->size()) + 1, 0, 1, 3);
}

}  // namespace palprig::gui
