// Mesh convergence: halving the element size changes the peak contact stress by less than 3 %
// (paper 002's fingertip pressed into its healthy tissue), and the contact force by much less.
// A block 20 mm high pressed 2 mm (the paper's is 100 mm, 7 mm deep): the suite runs twice in CI
// (release and under the sanitizers), and the paper's case at 1 and 0.5 mm takes about a minute;
// bench/bench_fe_paper002 measures that one (docs/finite-element.md, "Verification"). Here the
// two meshes agree to 0.1 % (11 s of CPU for both on the development machine).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mechanics/contact_problems.hpp"

namespace palprig::mechanics {
namespace {

ContactStep pressed(double element_mm) {
  TissueBlock block;  // paper 002's tissue (Table 1), free sides
  block.height_mm = 20;
  IndentationOptions o;
  o.solve.element_mm = element_mm;
  o.depth_mm = 2;
  o.step_mm = 1;
  return run_indentation(FingertipBody{}, block, o).steps.back();
}

TEST(MeshConvergence, HalvingTheElementsChangesThePeakByLessThanThreePercent) {
  const ContactStep coarse = pressed(1.0), fine = pressed(0.5);
  ASSERT_GT(coarse.peak_kPa, 1.0);
  std::printf("mesh convergence: peak %.4f kPa (1 mm), %.4f kPa (0.5 mm); force %.3f, %.3f N/m\n", coarse.peak_kPa,
              fine.peak_kPa, coarse.force_N_per_m, fine.force_N_per_m);
  EXPECT_LT(std::abs(fine.peak_kPa / coarse.peak_kPa - 1), 0.03)
      << "1 mm: " << coarse.peak_kPa << " kPa, 0.5 mm: " << fine.peak_kPa << " kPa";
  EXPECT_LT(std::abs(fine.force_N_per_m / coarse.force_N_per_m - 1), 0.01);
  EXPECT_NEAR(fine.peak_s_mm, 0.0, 0.6) << "the peak is under the middle of the fingertip";
  // The contact stress integrates to the contact force (the smoothing keeps the load).
  double integral = 0;
  for (std::size_t i = 0; i + 1 < fine.profile.size(); ++i)
    integral +=
        (fine.profile[i].pressure_kPa + fine.profile[i + 1].pressure_kPa) / 2 *
        std::hypot(fine.profile[i + 1].x_mm - fine.profile[i].x_mm, fine.profile[i + 1].y_mm - fine.profile[i].y_mm);
  EXPECT_NEAR(integral, fine.force_N_per_m, 0.03 * fine.force_N_per_m);
}

}  // namespace
}  // namespace palprig::mechanics
