#pragma once
// FingerGauge: one finger's pressures as a vertical gauge: the setpoint as the filled bar
// (coloured by pressure), the target as a black tick, the regulator's monitor as an orange tick,
// and p_max as a red line, with the three values in kPa underneath, and the rendering error: the
// RMS of monitor - target over the last 5 s (models/rolling_rms.hpp), so an experimenter sees
// when a rig drifts from its calibration while it runs.
#include <QWidget>
#include <cmath>

#include "models/rolling_rms.hpp"

namespace palprig::gui {

class FingerGauge final : public QWidget {
  Q_OBJECT
 public:
  FingerGauge(int finger, QWidget* parent = nullptr);
  // t_s: the record's time (the rendering error's window runs on it).
  void set_values(double target_kPa, double setpoint_kPa, double monitor_kPa, double p_max_kPa,
                  double t_s = std::nan(""));
  double rendering_error_rms_kPa() const noexcept { return error_.rms_kPa(); }
  double setpoint_kPa() const noexcept { return setpoint_; }
  double target_kPa() const noexcept { return target_; }
  QSize sizeHint() const override { return {110, 236}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  int finger_;
  double target_ = 0, setpoint_ = 0, monitor_ = 0, p_max_ = 60, scale_max_ = 66;
  RollingRms error_{5.0};
};

}  // namespace palprig::gui
