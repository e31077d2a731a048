#pragma once
// The material laws of paper 002's finite-element model (section 2.3, Table 1), as data: what a
// fingertip, tissue or actuator file names and what mechanics/ turns into a strain energy.
//
//   Ogden, one term, ABAQUS's form (eq. 1):  U = 2 mu / alpha^2 (l1^alpha + l2^alpha + l3^alpha - 3)
//     with the deviatoric stretches; incompressible (Table 1's 1/D = 0). Its initial shear
//     modulus is mu, whatever the sign of alpha (the skin's alpha is -10.898).
//   Arruda-Boyce, ABAQUS's five-term series (eq. 2, with its I1 the first invariant of the
//     deviatoric right Cauchy-Green tensor and the series' "+ 3^i" read as "- 3^i"):
//     U = mu sum_i C_i / lambda_m^(2i-2) (I1^i - 3^i), C = 1/2, 1/20, 11/1050, 19/7000, 519/673750;
//     incompressible. Its initial shear modulus is mu (1 + 3/(5 lm^2) + 99/(175 lm^4) + ...), so
//     the tissue's mu = 1.850 kPa with lambda_m = 1.05 is a modulus of 5.5 kPa (E 16 kPa).
//   Linear elastic (bone, nail, membrane): Young's modulus and Poisson's ratio; in large
//     deformation mechanics/ uses Saint Venant-Kirchhoff (the same law at small strain, which
//     is all these stiff parts see). The membrane's E comes from its Shore A hardness (eq. 3-4).
#include <string>

namespace palprig {

enum class MaterialKind { ogden, arruda_boyce, linear_elastic };
const char* to_string(MaterialKind k) noexcept;

struct MaterialLaw {
  MaterialKind kind = MaterialKind::linear_elastic;
  double mu_kPa = 0;           // Ogden, Arruda-Boyce
  double alpha = 0;            // Ogden exponent
  double locking_stretch = 0;  // Arruda-Boyce lambda_m (> 1)
  double youngs_kPa = 0;       // linear elastic
  double poisson = 0;          // linear elastic, in [0, 0.5)
  double density_kg_m3 = 0;    // Table 1's density: kept for the record (a static analysis ignores it)

  static MaterialLaw ogden(double mu_kPa, double alpha);
  static MaterialLaw arruda_boyce(double mu_kPa, double locking_stretch);
  static MaterialLaw linear_elastic(double youngs_kPa, double poisson);

  bool incompressible() const noexcept { return kind != MaterialKind::linear_elastic; }
  // The small-strain shear modulus (kPa).
  double initial_shear_modulus_kPa() const noexcept;
  // The small-strain Young's modulus (kPa): 3 mu for the incompressible laws.
  double initial_youngs_kPa() const noexcept;
  // The same law `factor` times stiffer (mu or E scaled; exponents and locking stretch kept).
  MaterialLaw scaled(double factor) const noexcept;
  // "Ogden mu 19.34 kPa, alpha -4.4894" and the like, for reports.
  std::string describe() const;
};

// Paper 002 eq. 3-4 (after Gent): log10 E[MPa] = 0.0235 S - 0.6403, with S = S_A for Shore A
// 20..80 and S = S_D + 50 for Shore D 30..85. Returns E in kPa; the caller checks the range.
double youngs_from_shore_a_kPa(double shore_a) noexcept;
double youngs_from_shore_d_kPa(double shore_d) noexcept;

// Table 1 of paper 002, the defaults of the shipped files.
namespace table1 {
MaterialLaw bone();            // linear elastic, E 17 GPa, nu 0.3
MaterialLaw nail();            // linear elastic, E 170 MPa, nu 0.3
MaterialLaw finger_tissue();   // Ogden, mu 19.34 kPa, alpha -4.4894
MaterialLaw skin();            // Ogden, mu 1.8428 kPa, alpha -10.898
MaterialLaw soft_tissue();     // Arruda-Boyce, mu 1.850 kPa, lambda_m 1.05
MaterialLaw tumor();           // Arruda-Boyce, mu 73.4 kPa, lambda_m 1.01
MaterialLaw membrane();        // linear elastic, E 1.994 MPa (Shore A 40), nu 0.49
MaterialLaw silicone_layer();  // Arruda-Boyce, mu 4.98 kPa, lambda_m 1.05
}  // namespace table1

}  // namespace palprig
