// StiffnessField: moduli at known points, the log-scale normalisation, and what a finger feels
// as a function of depth and pressing force (deep small tumors need more force than shallow
// large ones; bone is hard at any force), respiration and the body outline.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "models/stiffness_field.hpp"

using namespace palprig;

namespace {

TissueDefinition block(double modulus_kPa = 14.7) {
  TissueDefinition d;
  d.body = {{80, 60}, 80, 60, 16};
  d.layers = {{"tissue", 60, modulus_kPa}};
  d.felt = {14.7, 21.9};
  return d;
}

Inclusion sphere(const char* name, Point3_mm c, double r, double modulus_kPa,
                 InclusionKind kind = InclusionKind::tumor) {
  Inclusion i;
  i.name = name;
  i.kind = kind;
  i.shape.sphere(c, r);
  i.stiffness_kPa = modulus_kPa;
  return i;
}

// The smallest force (0.1 N steps) at which the finger over (x, y) feels at least `level`.
double force_to_feel(const StiffnessField& f, Point2_mm at, double level) {
  for (double F = 0.1; F <= 10.0; F += 0.1)
    if (f.felt_stiffness(at, F, 0) >= level) return F;
  return 1e9;
}

}  // namespace

TEST(StiffnessField, ModulusAtKnownPointsLayersAndInclusions) {
  TissueDefinition d = block();
  d.layers = {{"skin", 2, 40}, {"fat", 8, 4}, {"muscle", 30, 15}};
  d.support_kPa = 5000;
  d.inclusions.push_back(sphere("organ", {50, 50, 20}, 8, 30, InclusionKind::organ));
  d.inclusions.push_back(sphere("tumor", {50, 50, 20}, 3, 90));  // inside the organ, listed later: wins
  const StiffnessField f(d);
  EXPECT_EQ(f.modulus_kPa({10, 60, 1}, 0), 40);
  EXPECT_EQ(f.modulus_kPa({10, 60, 5}, 0), 4);
  EXPECT_EQ(f.modulus_kPa({10, 60, 25}, 0), 15);
  EXPECT_EQ(f.modulus_kPa({10, 60, 45}, 0), 5000);  // below the stack: the support
  EXPECT_EQ(f.modulus_kPa({50, 50, 20}, 0), 90);
  EXPECT_EQ(f.modulus_kPa({50, 56, 20}, 0), 30);
  EXPECT_EQ(f.modulus_kPa({50, 59, 20}, 0), 15);
  EXPECT_EQ(f.modulus_kPa({-5, 60, 5}, 0), 0);  // off the body: air
  EXPECT_EQ(f.layer_at(1), 0);
  EXPECT_EQ(f.layer_at(9.9), 1);
  EXPECT_EQ(f.layer_at(100), 2);
}

TEST(StiffnessField, LogScaleNormalisation) {
  const StiffnessField f(block());
  EXPECT_DOUBLE_EQ(f.normalised(14.7), 0.0);
  EXPECT_DOUBLE_EQ(f.normalised(21.9), 1.0);
  EXPECT_NEAR(f.normalised(std::sqrt(14.7 * 21.9)), 0.5, 1e-12);  // geometric midpoint
  EXPECT_DOUBLE_EQ(f.normalised(5.0), 0.0);
  EXPECT_DOUBLE_EQ(f.normalised(1e6), 1.0);
}

TEST(StiffnessField, HomogeneousTissueFeelsItsOwnLevelAtAnyForce) {
  const StiffnessField soft(block(14.7)), hard(block(21.9)), middle(block(std::sqrt(14.7 * 21.9)));
  for (double F : {0.1, 0.5, 2.0, 6.0}) {
    EXPECT_NEAR(soft.felt_stiffness({80, 60}, F, 0), 0.0, 1e-12);
    EXPECT_NEAR(hard.felt_stiffness({80, 60}, F, 0), 1.0, 1e-12);
    EXPECT_NEAR(middle.felt_stiffness({80, 60}, F, 0), 0.5, 1e-9);
  }
}

TEST(StiffnessField, PressModelMatchesPaper002AndHertzScaling) {
  const PressModel p;
  EXPECT_NEAR(p.indentation_mm(2.0), 7.0, 1e-12);        // the FE study's 7 mm press
  EXPECT_NEAR(p.indentation_mm(16.0), 7.0 * 4.0, 1e-9);  // (8)^(2/3) = 4
  EXPECT_NEAR(p.contact_radius_mm(2.0), std::sqrt(8.0 * 7.0), 1e-12);
  EXPECT_NEAR(p.reach_mm(2.0), 4 * std::sqrt(56.0), 1e-12);
  EXPECT_EQ(p.indentation_mm(0), 0);
  EXPECT_EQ(p.contact_radius_mm(0), p.min_contact_radius_mm);
}

TEST(StiffnessField, DeepSmallTumorNeedsMoreForceThanShallowLargeOne) {
  TissueDefinition d = block();
  d.inclusions.push_back(sphere("shallow large", {40, 60, 11}, 10, 21.9));  // top 1 mm under the skin
  d.inclusions.push_back(sphere("deep small", {120, 60, 20}, 4, 21.9));     // top 16 mm down
  const StiffnessField f(d);
  const double shallow = force_to_feel(f, {40, 60}, 0.05), deep = force_to_feel(f, {120, 60}, 0.05);
  EXPECT_LT(shallow, 0.5);
  EXPECT_GT(deep, 3 * shallow);
  EXPECT_LT(deep, 10.0);  // it can be felt, with enough force
  // The deep one's share grows as the press reaches further down.
  double previous = -1;
  for (double F : {0.5, 1.0, 2.0, 4.0, 8.0}) {
    const double s = f.felt_stiffness({120, 60}, F, 0);
    EXPECT_GT(s, previous) << F;
    previous = s;
  }
  // At the reference press the shallow large tumor is felt far more than the deep small one.
  EXPECT_GT(f.felt_stiffness({40, 60}, 2.0, 0), 3 * f.felt_stiffness({120, 60}, 2.0, 0));
}

TEST(StiffnessField, BoneUnderTheSkinIsHardAtAnyForce) {
  TissueDefinition d = block(5);
  d.felt = {5, 300};
  d.layers = {{"skin", 2, 40}, {"contents", 100, 5}};
  Inclusion rib;
  rib.name = "rib";
  rib.kind = InclusionKind::bone;
  rib.shape.tube({0, 60, 7}, {160, 60, 7}, 5);  // top 2 mm under the skin
  rib.stiffness_kPa = 1e7;
  d.inclusions.push_back(rib);
  const StiffnessField f(d);
  for (double F : {0.1, 0.5, 1.0, 2.0, 6.0}) EXPECT_GT(f.felt_stiffness({80, 60}, F, 0), 0.9) << F;
  // The same volume of merely stiff tissue (not bone) is diluted by the soft tissue around it.
  d.inclusions[0].kind = InclusionKind::organ;
  const StiffnessField g(d);
  EXPECT_LT(g.felt_stiffness({80, 60}, 2.0, 0), 0.9);
}

TEST(StiffnessField, FeltFallsOffAcrossATumorEdge) {
  TissueDefinition d = block();
  d.inclusions.push_back(sphere("T", {80, 60, 7}, 6, 21.9));
  const StiffnessField f(d);
  double previous = 2;
  for (double dx : {0.0, 3.0, 6.0, 9.0, 12.0, 20.0}) {
    const double s = f.felt_stiffness({80 + dx, 60}, 2.0, 0);
    EXPECT_LE(s, previous + 1e-12) << dx;
    previous = s;
  }
  EXPECT_GT(f.felt_stiffness({80, 60}, 2.0, 0), 0.4);
  EXPECT_NEAR(f.felt_stiffness({110, 60}, 2.0, 0), 0.0, 1e-12);
}

TEST(StiffnessField, RespirationMovesTheOrganUnderAFixedFinger) {
  TissueDefinition d = block();
  d.respiration.period_s = 4;
  Inclusion liver = sphere("liver", {80, 40, 12}, 10, 21.9, InclusionKind::organ);
  liver.breathing_excursion_mm = {0, 16, 0};  // toward the feet at full inspiration
  d.inclusions.push_back(liver);
  const StiffnessField f(d);
  const Point2_mm finger{80, 60};  // 20 mm below the organ's centre at rest: just off its edge
  const double out = f.felt_stiffness(finger, 2, 0.0);
  const double in = f.felt_stiffness(finger, 2, 2.0);  // full inspiration: centre at y = 56
  EXPECT_GT(in, out + 0.3);
  EXPECT_NEAR(f.felt_stiffness(finger, 2, 4.0), out, 1e-9);  // one period later, as at rest
  EXPECT_NEAR(f.felt_stiffness(finger, 2, 1.0), f.felt_stiffness(finger, 2, 3.0), 1e-9);
  EXPECT_NEAR(d.respiration.inspiration(1.0), 0.5, 1e-12);
}

TEST(StiffnessField, LayerReportedIsTheOnePressedInto) {
  TissueDefinition d = block();
  d.layers = {{"skin", 2, 40}, {"fat", 8, 4}, {"muscle", 30, 15}};
  const StiffnessField f(d);
  EXPECT_EQ(f.sample({80, 60}, 0.1, 0).layer, 0);  // sinks 1.5 mm: skin
  EXPECT_EQ(f.sample({80, 60}, 2.0, 0).layer, 1);  // 7 mm: fat
  EXPECT_EQ(f.sample({80, 60}, 6.0, 0).layer, 2);  // 14.6 mm: muscle
}

TEST(StiffnessField, OffTheBodyNothingIsFelt) {
  TissueDefinition d = block(21.9);
  d.body = {{80, 60}, 50, 40, 6};
  const StiffnessField f(d);
  const TissueSample off = f.sample({5, 5}, 2, 0);
  EXPECT_EQ(off.stiffness, 0);
  EXPECT_EQ(off.layer, -1);
  EXPECT_GT(f.felt_stiffness({80, 60}, 2, 0), 0.99);
  EXPECT_EQ(f.sample({std::nan(""), 5}, 2, 0).stiffness, 0);
  const SceneBounds b = f.bounds();
  EXPECT_EQ(b.x0_mm, 30);
  EXPECT_EQ(b.y1_mm, 100);
}

TEST(StiffnessField, RefusesDefinitionsThatCannotBeTissue) {
  TissueDefinition d = block();
  d.layers.clear();
  EXPECT_THROW(StiffnessField{d}, palprig::BadInput);
  d = block();
  d.layers[0].thickness_mm = -1;
  EXPECT_THROW(StiffnessField{d}, palprig::BadInput);
  d = block();
  d.felt = {21.9, 14.7};
  EXPECT_THROW(StiffnessField{d}, palprig::BadInput);
  d = block();
  d.inclusions.push_back(sphere("T", {0, 0, 5}, 2, -3));
  EXPECT_THROW(StiffnessField{d}, palprig::BadInput);
  d = block();
  d.body.half_width_mm = 0;
  EXPECT_THROW(StiffnessField{d}, palprig::BadInput);
}
