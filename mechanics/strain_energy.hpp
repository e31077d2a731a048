#pragma once
// The laws of models/material_law.hpp in 2D: their strain energy per unit reference area with its
// gradient and Hessian in the displacement gradient (contact_solver.cpp hands them to GetFEM as
// nonlinear operators), and their stresses in closed form for the von Mises field and the
// verification tests.
//
// Why the derivatives are computed here and not by GetFEM: written as weak-form expressions, the
// energies were derived symbolically by GetFEM twice at every assembly (it compiles a model's
// terms anew each time), which was more than half of a solve; as operators the same solve is
// about five times faster, to the last digits the same.
//
// Why written here: GetFEM's own 2D hyperelastic laws are plane strain only, it has no Ogden law
// and no Arruda-Boyce law, and its weak-form language has no eigenvalue operator. So:
// - plane stress, incompressible: the out-of-plane stretch is 1 / det(F) exactly (no pressure
//   field: the plane-stress condition fixes the pressure), the energy is that of the 3D law at
//   C = diag(C2, 1/det(C2));
// - plane strain, incompressible: the energy of the deviatoric stretches plus p (J - 1), p a
//   pressure field (quadratic displacements, linear continuous pressure: Taylor-Hood);
// - Ogden needs the principal stretches: the eigenvalues of the 2 x 2 right Cauchy-Green tensor,
//   (tr C +- sqrt(tr^2 C - 4 det C)) / 2, with 1e-10 added under the root (the root's derivative
//   is infinite at C = I, where the two eigenvalues meet; the offset costs about 1e-12 of mu);
// - linear elastic parts (bone, nail, membrane): Saint Venant-Kirchhoff, plane stress with
//   lambda* = 2 lambda mu / (lambda + 2 mu).
#include <array>
#include <string>

#include "mechanics/second_order_dual.hpp"
#include "models/material_law.hpp"

namespace palprig::mechanics {

enum class PlaneMode { plane_strain, plane_stress };
const char* to_string(PlaneMode m) noexcept;

// The energy at an in-plane displacement gradient Grad_u, given as GetFEM orders it (component
// (i, j) = du_i/dx_j at i + 2 j), with its derivatives in those four components. For an
// incompressible law in plane strain the energy is the deviatoric part's: the pressure's term
// p (J - 1) stays in the weak form (contact_solver.cpp).
SecondOrderDual strain_energy(const MaterialLaw& law, PlaneMode mode, const std::array<double, 4>& grad_u);

// Whether the law needs a pressure field in this mode.
bool needs_pressure(const MaterialLaw& law, PlaneMode mode) noexcept;

// Von Mises stress (kPa) of the Cauchy stress for an in-plane deformation gradient
// F = [[F11, F12], [F21, F22]] (row-major). For incompressible plane strain it does not depend
// on the pressure field (a pressure adds to every normal stress alike).
double von_mises_kPa(const MaterialLaw& law, PlaneMode mode, const std::array<double, 4>& F) noexcept;

// Homogeneous uniaxial compression or stretch along y by `stretch`, free across (sigma_xx = 0;
// and sigma_zz = 0 in plane stress): the nominal stress P_yy (force per reference area), from
// the closed forms of each law (the patch test's oracle).
double uniaxial_nominal_stress_kPa(const MaterialLaw& law, PlaneMode mode, double stretch);
// The same state's lateral stretch (lambda_x).
double uniaxial_lateral_stretch(const MaterialLaw& law, PlaneMode mode, double stretch);

}  // namespace palprig::mechanics
