#include "models/material_law.hpp"

#include <cmath>
#include <sstream>

namespace palprig {

const char* to_string(MaterialKind k) noexcept {
  switch (k) {
    case MaterialKind::ogden: return "ogden";
    case MaterialKind::arruda_boyce: return "arruda_boyce";
    case MaterialKind::linear_elastic: return "linear_elastic";
  }
  return "?";
}

MaterialLaw MaterialLaw::ogden(double mu_kPa, double alpha) {
  MaterialLaw m;
  m.kind = MaterialKind::ogden;
  m.mu_kPa = mu_kPa;
  m.alpha = alpha;
  return m;
}

MaterialLaw MaterialLaw::arruda_boyce(double mu_kPa, double locking_stretch) {
  MaterialLaw m;
  m.kind = MaterialKind::arruda_boyce;
  m.mu_kPa = mu_kPa;
  m.locking_stretch = locking_stretch;
  return m;
}

MaterialLaw MaterialLaw::linear_elastic(double youngs_kPa, double poisson) {
  MaterialLaw m;
  m.kind = MaterialKind::linear_elastic;
  m.youngs_kPa = youngs_kPa;
  m.poisson = poisson;
  return m;
}

double MaterialLaw::initial_shear_modulus_kPa() const noexcept {
  switch (kind) {
    case MaterialKind::ogden: return mu_kPa;
    case MaterialKind::arruda_boyce: {
      // d^2U/dI1 at I1 = 3 times 2: mu sum_i i C_i 3^(i-1) / lm^(2i-2) (ABAQUS's closed form).
      const double l2 = 1.0 / (locking_stretch * locking_stretch);
      return mu_kPa * (1 + 3.0 / 5 * l2 + 99.0 / 175 * l2 * l2 + 513.0 / 875 * l2 * l2 * l2 +
                       42039.0 / 67375 * l2 * l2 * l2 * l2);
    }
    case MaterialKind::linear_elastic: return youngs_kPa / (2 * (1 + poisson));
  }
  return 0;
}

double MaterialLaw::initial_youngs_kPa() const noexcept {
  return kind == MaterialKind::linear_elastic ? youngs_kPa : 3 * initial_shear_modulus_kPa();
}

MaterialLaw MaterialLaw::scaled(double factor) const noexcept {
  MaterialLaw m = *this;
  m.mu_kPa *= factor;
  m.youngs_kPa *= factor;
  return m;
}

std::string MaterialLaw::describe() const {
  std::ostringstream o;
  switch (kind) {
    case MaterialKind::ogden: o << "Ogden mu " << mu_kPa << " kPa, alpha " << alpha; break;
    case MaterialKind::arruda_boyce: o << "Arruda-Boyce mu " << mu_kPa << " kPa, lambda_m " << locking_stretch; break;
    case MaterialKind::linear_elastic: o << "linear elastic E " << youngs_kPa << " kPa, nu " << poisson; break;
  }
  return o.str();
}

double youngs_from_shore_a_kPa(double shore_a) noexcept { return 1000.0 * std::pow(10.0, 0.0235 * shore_a - 0.6403); }

double youngs_from_shore_d_kPa(double shore_d) noexcept { return youngs_from_shore_a_kPa(shore_d + 50); }

namespace table1 {
namespace {
MaterialLaw with_density(MaterialLaw m, double rho) {
  m.density_kg_m3 = rho;
  return m;
}
}  // namespace
MaterialLaw bone() { return with_density(MaterialLaw::linear_elastic(17e6, 0.3), 2700); }
MaterialLaw nail() { return with_density(MaterialLaw::linear_elastic(170e3, 0.3), 2000); }
MaterialLaw finger_tissue() { return with_density(MaterialLaw::ogden(19.34, -4.4894), 1000); }
MaterialLaw skin() { return with_density(MaterialLaw::ogden(1.8428, -10.898), 1000); }
MaterialLaw soft_tissue() { return with_density(MaterialLaw::arruda_boyce(1.850, 1.05), 850); }
MaterialLaw tumor() { return with_density(MaterialLaw::arruda_boyce(73.4, 1.01), 1000); }
MaterialLaw membrane() { return with_density(MaterialLaw::linear_elastic(1994, 0.49), 970); }
MaterialLaw silicone_layer() { return with_density(MaterialLaw::arruda_boyce(4.98, 1.05), 980); }
}  // namespace table1

}  // namespace palprig
