#pragma once
// FingerGauge: one finger's pressures as a vertical gauge: the setpoint as the filled bar
// (coloured by pressure), the target as a black tick, the regulator's monitor as an orange tick,
// and p_max as a red line, with the three values in kPa underneath.
#include <QWidget>

namespace palprig::gui {

class FingerGauge final : public QWidget {
  Q_OBJECT
 public:
  FingerGauge(int finger, QWidget* parent = nullptr);
  void set_values(double target_kPa, double setpoint_kPa, double monitor_kPa, double p_max_kPa);
  double setpoint_kPa() const noexcept { return setpoint_; }
  double target_kPa() const noexcept { return target_; }
  QSize sizeHint() const override { return {110, 220}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  int finger_;
  double target_ = 0, setpoint_ = 0, monitor_ = 0, p_max_ = 60, scale_max_ = 66;
};

}  // namespace palprig::gui
