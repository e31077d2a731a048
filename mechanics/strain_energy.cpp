#include "mechanics/strain_energy.hpp"

#include <cmath>

namespace palprig::mechanics {

namespace {

// Arruda-Boyce's series coefficients (ABAQUS): C_i for i = 1..5.
constexpr std::array<double, 5> kArrudaBoyce = {1.0 / 2, 1.0 / 20, 11.0 / 1050, 19.0 / 7000, 519.0 / 673750};

struct Lame {
  double lambda, mu;
};
Lame lame(const MaterialLaw& law, PlaneMode mode) {
  const double E = law.youngs_kPa, nu = law.poisson;
  const double mu = E / (2 * (1 + nu));
  double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  if (mode == PlaneMode::plane_stress) lambda = 2 * lambda * mu / (lambda + 2 * mu);
  return {lambda, mu};
}

// dU/dI1 of Arruda-Boyce.
double arruda_boyce_slope(const MaterialLaw& law, double i1) {
  double sum = 0, lm_power = 1, i1_power = 1;
  for (int i = 1; i <= 5; ++i) {
    sum += i * kArrudaBoyce[std::size_t(i - 1)] * i1_power / lm_power;
    i1_power *= i1;
    lm_power *= law.locking_stretch * law.locking_stretch;
  }
  return law.mu_kPa * sum;
}

// Kirchhoff principal stresses of an incompressible law (its isochoric part) at principal
// stretches l (product 1): tau_i = l_i dU/dl_i.
std::array<double, 3> kirchhoff(const MaterialLaw& law, const std::array<double, 3>& l) {
  std::array<double, 3> tau{};
  if (law.kind == MaterialKind::ogden) {
    for (std::size_t i = 0; i < 3; ++i) tau[i] = 2 * law.mu_kPa / law.alpha * std::pow(l[i], law.alpha);
  } else {
    const double i1 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
    const double slope = arruda_boyce_slope(law, i1);
    for (std::size_t i = 0; i < 3; ++i) tau[i] = 2 * slope * l[i] * l[i];
  }
  return tau;
}

double von_mises_of(const std::array<double, 3>& s, double shear = 0) {
  return std::sqrt(0.5 *
                       ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - s[2]) * (s[1] - s[2]) + (s[2] - s[0]) * (s[2] - s[0])) +
                   3 * shear * shear);
}

}  // namespace

const char* to_string(PlaneMode m) noexcept { return m == PlaneMode::plane_stress ? "plane stress" : "plane strain"; }

bool needs_pressure(const MaterialLaw& law, PlaneMode mode) noexcept {
  return law.incompressible() && mode == PlaneMode::plane_strain;
}

SecondOrderDual strain_energy(const MaterialLaw& law, PlaneMode mode, const std::array<double, 4>& grad_u) {
  // F = I + Grad_u, component (i, j) at i + 2 j (GetFEM's order), each a variable.
  std::array<SecondOrderDual, 4> F;
  for (int k = 0; k < 4; ++k)
    F[std::size_t(k)] = SecondOrderDual::variable(k, grad_u[std::size_t(k)] + ((k == 0 || k == 3) ? 1.0 : 0.0));
  const SecondOrderDual c11 = F[0] * F[0] + F[1] * F[1], c22 = F[2] * F[2] + F[3] * F[3],
                        c12 = F[0] * F[2] + F[1] * F[3];
  const SecondOrderDual trace = c11 + c22, det = c11 * c22 - c12 * c12;
  if (law.kind == MaterialKind::linear_elastic) {  // Saint Venant-Kirchhoff: E = (C - I) / 2
    const Lame l = lame(law, mode);
    const SecondOrderDual e11 = 0.5 * (c11 + -1.0), e22 = 0.5 * (c22 + -1.0), e12 = 0.5 * c12;
    const SecondOrderDual trace_e = e11 + e22;
    return (l.lambda / 2) * (trace_e * trace_e) + l.mu * (e11 * e11 + e22 * e22 + 2.0 * (e12 * e12));
  }
  // The first invariant and the principal stretches' squares of the (deviatoric) 3D tensor.
  const bool strain = mode == PlaneMode::plane_strain;
  const SecondOrderDual iso = strain ? pow(det, -1.0 / 3) : SecondOrderDual::constant(1);  // J^(-2/3)
  const SecondOrderDual out_of_plane = strain ? iso : pow(det, -1.0);  // the third principal C value
  if (law.kind == MaterialKind::ogden) {
    const SecondOrderDual root = pow(trace * trace - 4.0 * det + 1e-10, 0.5);
    const SecondOrderDual c1 = 0.5 * (iso * (trace + root)), c2 = 0.5 * (iso * (trace - root));
    const double half = law.alpha / 2;
    return (2 * law.mu_kPa / (law.alpha * law.alpha)) *
           (pow(c1, half) + pow(c2, half) + pow(out_of_plane, half) + -3.0);
  }
  const SecondOrderDual i1 = iso * trace + out_of_plane;
  SecondOrderDual energy, i1_power = SecondOrderDual::constant(1);
  double lm_power = 1, three_power = 1;
  for (std::size_t i = 1; i <= 5; ++i) {
    i1_power = i1_power * i1;
    three_power *= 3;
    energy = energy + (law.mu_kPa * kArrudaBoyce[i - 1] / lm_power) * (i1_power + -three_power);
    lm_power *= law.locking_stretch * law.locking_stretch;
  }
  return energy;
}

double von_mises_kPa(const MaterialLaw& law, PlaneMode mode, const std::array<double, 4>& F) noexcept {
  const double f11 = F[0], f12 = F[1], f21 = F[2], f22 = F[3];
  const double det = f11 * f22 - f12 * f21;
  if (!(det > 0)) return std::nan("");
  if (law.kind == MaterialKind::linear_elastic) {
    const Lame l = lame(law, mode);
    // E = (C - I) / 2, S = lambda tr(E) I + 2 mu E, sigma = F S F' / J.
    const double c11 = f11 * f11 + f21 * f21, c22 = f12 * f12 + f22 * f22, c12 = f11 * f12 + f21 * f22;
    const double e11 = (c11 - 1) / 2, e22 = (c22 - 1) / 2, e12 = c12 / 2, tr = e11 + e22;
    const double s11 = l.lambda * tr + 2 * l.mu * e11, s22 = l.lambda * tr + 2 * l.mu * e22, s12 = 2 * l.mu * e12;
    double j = det, szz = 0;
    if (mode == PlaneMode::plane_strain) {
      szz = l.lambda * tr / j;
    } else {  // the thickness stretch that makes S_zz = 0 with the 3D Lame constants
      const Lame l3 = lame(law, PlaneMode::plane_strain);
      j *= std::sqrt(std::max(1e-12, 1 - 2 * l3.lambda / (l3.lambda + 2 * l3.mu) * tr));
    }
    // F S
    const double a11 = f11 * s11 + f12 * s12, a12 = f11 * s12 + f12 * s22;
    const double a21 = f21 * s11 + f22 * s12, a22 = f21 * s12 + f22 * s22;
    const double sxx = (a11 * f11 + a12 * f12) / j, syy = (a21 * f21 + a22 * f22) / j,
                 sxy = (a11 * f21 + a12 * f22) / j;
    return von_mises_of({sxx, syy, szz}, sxy);
  }
  const double c11 = f11 * f11 + f21 * f21, c22 = f12 * f12 + f22 * f22, c12 = f11 * f12 + f21 * f22;
  const double tr = c11 + c22, dc = c11 * c22 - c12 * c12;
  const double root = std::sqrt(std::max(0.0, tr * tr - 4 * dc));
  const double l1 = std::sqrt((tr + root) / 2), l2 = std::sqrt(std::max(1e-300, (tr - root) / 2));
  std::array<double, 3> stretch{l1, l2, 1 / (l1 * l2)};
  double j = 1;
  if (mode == PlaneMode::plane_strain) {  // the deviatoric stretches of (l1, l2, 1)
    j = l1 * l2;
    const double iso = std::cbrt(1 / j);
    stretch = {l1 * iso, l2 * iso, iso};
  }
  return von_mises_of(kirchhoff(law, stretch)) / j;
}

double uniaxial_lateral_stretch(const MaterialLaw& law, PlaneMode mode, double stretch) {
  if (law.kind == MaterialKind::linear_elastic) {
    const Lame l = lame(law, mode);
    const double eyy = (stretch * stretch - 1) / 2;
    const double exx = -l.lambda * eyy / (l.lambda + 2 * l.mu);
    return std::sqrt(1 + 2 * exx);
  }
  return mode == PlaneMode::plane_strain ? 1 / stretch : 1 / std::sqrt(stretch);
}

double uniaxial_nominal_stress_kPa(const MaterialLaw& law, PlaneMode mode, double stretch) {
  if (law.kind == MaterialKind::linear_elastic) {
    const Lame l = lame(law, mode);
    const double lx = uniaxial_lateral_stretch(law, mode, stretch);
    const double eyy = (stretch * stretch - 1) / 2, exx = (lx * lx - 1) / 2;
    return stretch * (l.lambda * (exx + eyy) + 2 * l.mu * eyy);
  }
  const double lx = uniaxial_lateral_stretch(law, mode, stretch);
  const double lz = mode == PlaneMode::plane_strain ? 1.0 : lx;
  const auto tau = kirchhoff(law, {lx, stretch, lz});
  // sigma_xx = tau_x - p = 0 fixes p; sigma_yy = tau_y - tau_x; P_yy = sigma_yy / stretch (J = 1).
  return (tau[1] - tau[0]) / stretch;
}

}  // namespace palprig::mechanics
