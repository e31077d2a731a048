// The finite-element model against closed forms: a patch test (a block compressed homogeneously:
// its reaction and lateral stretch exact for each law, plane strain and plane stress) and
// Hertz's 2D contact (a stiff cylinder on an elastic block: contact half-width and peak
// pressure within 5 %). Coarse meshes on purpose: CI runs every suite twice (release and under
// the sanitizers), so each case here solves in seconds; the paper's model at the paper's mesh is
// measured by bench/bench_fe_paper002 and reported in docs/finite-element.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>

#include "mechanics/body_meshes.hpp"
#include "mechanics/contact_problems.hpp"
#include "mechanics/contact_solver.hpp"
#include "mechanics/strain_energy.hpp"

namespace palprig::mechanics {
namespace {

// A 10 x 10 mm block of one law, 4 x 4 elements, on rollers at its bottom and left side, its top
// pushed down on rollers by `shortening_mm`, its right side free.
struct Patch {
  double reaction_per_mm = 0;  // the force on the top, per unit thickness (kPa mm)
  double lateral_stretch = 0;  // of the top right corner
  bool converged = false;
};

Patch compress(const MaterialLaw& law, PlaneMode mode, double shortening_mm) {
  TissueBlock block;
  block.width_mm = 10;
  block.height_mm = 10;
  BlockMeshSizes sizes;
  sizes.element_mm = 2.5;
  sizes.fine_half_width_mm = 5;
  sizes.fine_depth_mm = 10;
  ProblemSpec spec;
  spec.mesh = mesh_block(block, sizes);
  for (auto& n : spec.mesh.nodes) n.x_mm += 5;  // the left side at x = 0
  spec.materials = {law};
  spec.plane = mode;
  spec.rollers = {{"block_bottom"}, {"block_left"}, {"block_top"}};
  ContactSolver solver(spec);
  Patch out;
  for (int k = 1; k <= 4; ++k) {
    LoadState load;
    load.roller_mm["block_top"] = -shortening_mm * k / 4;  // along the top's outward normal (+y)
    out.converged = solver.solve(load).converged;
    if (!out.converged) return out;
  }
  out.reaction_per_mm = std::abs(solver.roller_reaction_per_mm("block_top"));
  const DeformedMesh d = solver.deformed();
  double right = 0;
  for (const auto& n : d.nodes) right = std::max(right, n.x_mm);
  out.lateral_stretch = right / 10.0;
  return out;
}

struct PatchCase {
  const char* name;
  MaterialLaw law;
  PlaneMode mode;
};

// Its name as the test's parameter (GoogleTest would print the struct's bytes, a pointer among
// them, into every test's name that ctest lists).
void PrintTo(const PatchCase& c, std::ostream* os) { *os << c.name; }

class PatchTest : public ::testing::TestWithParam<PatchCase> {};

TEST_P(PatchTest, HomogeneousCompressionIsExact) {
  const PatchCase& c = GetParam();
  const double stretch = 0.8;  // 20 % shorter
  const Patch p = compress(c.law, c.mode, 10 * (1 - stretch));
  ASSERT_TRUE(p.converged);
  const double expected = std::abs(uniaxial_nominal_stress_kPa(c.law, c.mode, stretch)) * 10.0;
  EXPECT_NEAR(p.reaction_per_mm, expected, 2e-3 * expected) << c.name;
  EXPECT_NEAR(p.lateral_stretch, uniaxial_lateral_stretch(c.law, c.mode, stretch), 1e-4) << c.name;
}

INSTANTIATE_TEST_SUITE_P(
    Laws, PatchTest,
    ::testing::Values(
        PatchCase{"Arruda-Boyce, plane strain", table1::soft_tissue(), PlaneMode::plane_strain},
        PatchCase{"Arruda-Boyce, plane stress", table1::soft_tissue(), PlaneMode::plane_stress},
        PatchCase{"Ogden skin, plane strain", table1::skin(), PlaneMode::plane_strain},
        PatchCase{"Ogden skin, plane stress", table1::skin(), PlaneMode::plane_stress},
        PatchCase{"Ogden tissue, plane stress", table1::finger_tissue(), PlaneMode::plane_stress},
        PatchCase{"linear elastic, plane strain", MaterialLaw::linear_elastic(100, 0.3), PlaneMode::plane_strain},
        PatchCase{"linear elastic, plane stress", MaterialLaw::linear_elastic(100, 0.3), PlaneMode::plane_stress}),
    [](const ::testing::TestParamInfo<PatchCase>& case_info) {
      std::string n = case_info.param.name;
      std::replace_if(
          n.begin(), n.end(), [](char ch) { return !std::isalnum(static_cast<unsigned char>(ch)); }, '_');
      return n;
    });

// The energy's derivatives the solver hands GetFEM (strain_energy): the gradient against central
// differences of the energy, the Hessian against central differences of the gradient, and a
// stress-free reference, for every law and mode of the patch test.
TEST_P(PatchTest, EnergyDerivativesAgreeWithFiniteDifferences) {
  const PatchCase& c = GetParam();
  const std::array<double, 4> at = {0.05, -0.03, 0.02, -0.1};  // Grad_u, component (i, j) at i + 2 j
  const SecondOrderDual w = strain_energy(c.law, c.mode, at);
  const double h = 1e-6;
  for (std::size_t k = 0; k < 4; ++k) {
    std::array<double, 4> up = at, down = at;
    up[k] += h;
    down[k] -= h;
    const SecondOrderDual wu = strain_energy(c.law, c.mode, up), wd = strain_energy(c.law, c.mode, down);
    const double scale = c.law.initial_youngs_kPa();
    EXPECT_NEAR(w.gradient[k], (wu.value - wd.value) / (2 * h), 1e-6 * scale) << c.name << " k " << k;
    for (std::size_t l = 0; l < 4; ++l) {
      EXPECT_NEAR(w.hessian[4 * k + l], (wu.gradient[l] - wd.gradient[l]) / (2 * h), 1e-5 * scale)
          << c.name << " k " << k << " l " << l;
      EXPECT_NEAR(w.hessian[4 * k + l], w.hessian[4 * l + k], 1e-9 * scale) << c.name;
    }
  }
  const SecondOrderDual rest = strain_energy(c.law, c.mode, {0, 0, 0, 0});
  EXPECT_NEAR(rest.value, 0, 1e-9 * c.law.initial_youngs_kPa()) << c.name;
  // At rest an incompressible law in plane strain leaves its stress to the pressure field: its
  // deviatoric energy has no gradient there either.
  for (double g : rest.gradient) EXPECT_NEAR(g, 0, 1e-6 * c.law.initial_youngs_kPa()) << c.name;
}

// The closed forms themselves, at small strain: every law's small-strain modulus.
TEST(ClosedForms, SmallStrainModuli) {
  for (const MaterialLaw& law : {table1::soft_tissue(), table1::skin(), table1::finger_tissue(), table1::tumor()}) {
    const double mu = law.initial_shear_modulus_kPa();
    // Plane strain, incompressible: P = 4 mu eps; plane stress (uniaxial): P = 3 mu eps = E eps.
    EXPECT_NEAR(uniaxial_nominal_stress_kPa(law, PlaneMode::plane_strain, 0.999), -4 * mu * 1e-3,
                4e-3 * mu * 1e-3 * 10);
    EXPECT_NEAR(uniaxial_nominal_stress_kPa(law, PlaneMode::plane_stress, 0.999), -3 * mu * 1e-3,
                3e-3 * mu * 1e-3 * 10);
  }
  // Paper 002's tissue: mu 1.85 kPa with lambda_m 1.05 is an initial shear modulus of
  // mu (1 + 3/(5 lm^2) + 99/(175 lm^4) + 513/(875 lm^6) + 42039/(67375 lm^8)) = 1.85 x 2.8694
  // = 5.308 kPa (ABAQUS's Arruda-Boyce, worked by hand); the tumor's 73.4 kPa with 1.01, 73.4 x 3.2603.
  EXPECT_NEAR(table1::soft_tissue().initial_shear_modulus_kPa(), 5.308, 0.005);
  EXPECT_NEAR(table1::tumor().initial_shear_modulus_kPa(), 239.31, 0.05);
  // Eq. 3-4: Shore A 40 is 1.994 MPa.
  EXPECT_NEAR(youngs_from_shore_a_kPa(40), 1994, 1);
}

// Hertz, 2D (Johnson, Contact Mechanics, 5.2): a cylinder of radius R pressed with force P per
// unit length on a half-space: contact half-width a = sqrt(4 P R / (pi E*)), peak pressure
// p0 = 2 P / (pi a), with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
TEST(Hertz, CylinderOnHalfSpace) {
  const double R = 20, E_block = 100, nu = 0.3, E_cylinder = 1e5;
  FingertipBody cylinder;
  cylinder.width_mm = cylinder.height_mm = 2 * R;
  cylinder.skin_thickness_mm = 0.6;
  cylinder.bone_width_mm = cylinder.bone_height_mm = 10;
  cylinder.bone_centre_height_mm = R;
  cylinder.nail_width_mm = 0;
  cylinder.skin = cylinder.tissue = cylinder.nail = MaterialLaw::linear_elastic(E_cylinder, nu);
  FingertipMeshSizes fs;
  fs.element_mm = 0.3;
  fs.fine_height_mm = 1.5;
  fs.top_element_mm = 4;
  fs.tissue_rows = 6;
  fs.row_grading = 0.5;
  TissueBlock block;
  block.width_mm = 80;
  block.height_mm = 40;
  BlockMeshSizes bs;
  bs.element_mm = 0.3;
  bs.fine_half_width_mm = 4.5;
  bs.fine_depth_mm = 2;
  bs.growth = 0.3;
  bs.max_element_mm = 4;
  ProblemSpec spec;
  spec.mesh = mesh_fingertip(cylinder, fs);
  spec.mesh.append(mesh_block(block, bs), 1, 3);
  spec.materials = {cylinder.skin, cylinder.tissue, cylinder.nail, MaterialLaw::linear_elastic(E_block, nu)};
  spec.plane = PlaneMode::plane_strain;
  spec.held = {{"bone"}, {"block_bottom"}};
  spec.contact = ContactPair{"fingertip_contact", "block_top", E_block / 0.3, 1.0};
  ContactSolver solver(spec);
  for (int k = 1; k <= 2; ++k) {
    LoadState load;
    load.held_mm["bone"] = {0.0, -0.15 * k};
    ASSERT_TRUE(solver.solve(load).converged);
  }
  const double P = solver.contact_force_per_mm()[1];
  ContactStep step;
  step.profile = solver.contact_profile();
  summarise_profile(step);
  // The half-width from the profile's second moment (for Hertz's ellipse, a^2 / 4).
  double m0 = 0, m2 = 0;
  for (std::size_t i = 0; i + 1 < step.profile.size(); ++i) {
    const auto &l = step.profile[i], &r = step.profile[i + 1];
    const double dx = r.x_mm - l.x_mm, x = (l.x_mm + r.x_mm) / 2,
                 p = std::max(0.0, (l.pressure_kPa + r.pressure_kPa) / 2);
    if (std::abs(x) > R / 2) continue;  // the lower arc only
    m0 += p * dx;
    m2 += p * x * x * dx;
  }
  const double a_fe = 2 * std::sqrt(m2 / m0);
  const double e_star = 1 / ((1 - nu * nu) / E_block + (1 - nu * nu) / E_cylinder);
  const double a = std::sqrt(4 * P * R / (std::numbers::pi * e_star));
  const double p0 = 2 * P / (std::numbers::pi * a);
  ASSERT_GT(P, 0);
  // The figures docs/finite-element.md quotes ("Verification").
  std::printf("Hertz: P %.4f N/m, half-width %.4f mm (closed form %.4f), peak %.3f kPa (closed form %.3f)\n", P, a_fe,
              a, step.node_peak_kPa, p0);
  EXPECT_LT(a / R, 0.2) << "Hertz needs a small contact";
  EXPECT_NEAR(m0, P, 0.02 * P) << "the smoothed Cauchy stress carries the contact force";
  EXPECT_NEAR(a_fe, a, 0.05 * a);
  EXPECT_NEAR(step.node_peak_kPa, p0, 0.05 * p0);
}

}  // namespace
}  // namespace palprig::mechanics
