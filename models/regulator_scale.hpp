#pragma once
// How a proportional pressure regulator reads and reports pressure as a voltage: commanded
// 0-10 V (or 0-5 V) for 0-100 kPa, and a monitor output that may have an offset (SMC ITV
// monitors: 1-5 V for 0-100 kPa, i.e. 25 kPa/V with 0 kPa at 1 V). Shared by the Modbus and
// comedi backends.
namespace palprig {

struct RegulatorScale {
  double kPa_per_volt = 10.0;
  double volts_at_0_kPa = 0.0;

  double volts(double pressure_kPa) const noexcept { return volts_at_0_kPa + pressure_kPa / kPa_per_volt; }
  double pressure_kPa(double volts) const noexcept { return (volts - volts_at_0_kPa) * kPa_per_volt; }
};

}  // namespace palprig
