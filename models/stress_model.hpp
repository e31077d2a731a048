#pragma once
// From tissue stiffness and pressing force to the air pressure one actuator needs.
//
// StressModel (paper 002, FE study): pressing soft silicone 7 mm deep gives a peak fingertip
// stress of 4.990 kPa, pressing over a 10 mm hard nodule 7.967 kPa. Normalised stiffness s in
// 0..1 interpolates between them, and the stress scales with the pressing force relative to the
// force of that reference press (force_ratio = F / reference_force_N, capped):
//     stress(s, F) = force_ratio * (soft + s * (hard - soft))
//
// ActuatorModel (paper 002, fig. 12): the fingertip stress on the actuator is linear in air
// pressure, stress = slope * p + intercept, where intercept is the stress of the uninflated
// actuator under the reference press. That passive part scales with the press as the tissue
// stress does, so the pressure for a target stress at a given force ratio r is
//     p = (stress - r * intercept) / slope,     clamped at 0 (an actuator cannot pull).
// With the defaults, r = 1 and the hard-nodule stress 7.967 kPa give 11.75 kPa, the paper's
// figure, and soft tissue gives 0 kPa.
namespace palprig {

struct StressModel {
  double soft_stress_kPa = 4.990;
  double hard_stress_kPa = 7.967;
  double reference_force_N = 2.0;  // pressing force that matches the 7 mm FE press
  double max_force_ratio = 3.0;    // pressing harder than this saturates the cue

  double force_ratio(double force_N) const noexcept;
  double target_stress_kPa(double stiffness, double force_N) const noexcept;
};

struct ActuatorModel {
  double slope = (7.967 - 4.990) / 11.75;  // kPa of fingertip stress per kPa of air pressure
  double intercept_kPa = 4.990;            // stress with the actuator uninflated (reference press)

  double stress_kPa(double pressure_kPa) const noexcept { return slope * pressure_kPa + intercept_kPa; }
  // Inverse of stress_kPa at the reference press (force_ratio 1), not clamped.
  double pressure_for_stress_kPa(double stress_kPa) const noexcept { return (stress_kPa - intercept_kPa) / slope; }
  // Pressure for a target stress at a given force ratio, clamped at 0.
  double pressure_kPa(double stress_kPa, double force_ratio) const noexcept;
};

}  // namespace palprig
