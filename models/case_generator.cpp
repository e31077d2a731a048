#include "models/case_generator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/error.hpp"

namespace palprig {

namespace {

constexpr double kBackground_kPa = 14.7;  // paper 002's silicone
constexpr double kHardReference = 3.5;    // felt 1 at 3.5 x background: the easy cases' top contrast
constexpr double kGap_mm = 12.0;          // soft tissue between two tumors' outlines
constexpr int kPlacementTries = 2000;

// Portable numbers from the standard engine: the same on every standard library.
class CaseRandom {
 public:
  explicit CaseRandom(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  int integer(int lo, int hi) { return lo + static_cast<int>(engine_() % static_cast<std::uint64_t>(hi - lo + 1)); }

 private:
  std::mt19937_64 engine_;
};

struct Level {
  int min_count, max_count;
  double radius_lo, radius_hi;
  double cover_lo, cover_hi;  // centre depth minus radius
  double contrast_lo, contrast_hi;
};

Level level_of(CaseDifficulty d) {
  switch (d) {
    case CaseDifficulty::easy: return {1, 2, 8.0, 12.0, 1.0, 4.0, 2.5, 3.5};
    case CaseDifficulty::medium: return {1, 3, 5.0, 8.0, 4.0, 10.0, 1.7, 2.5};
    case CaseDifficulty::hard: return {0, 3, 3.0, 5.5, 8.0, 16.0, 1.25, 1.7};
  }
  return {1, 2, 8.0, 12.0, 1.0, 4.0, 2.5, 3.5};
}

}  // namespace

const char* to_string(CaseDifficulty d) noexcept {
  switch (d) {
    case CaseDifficulty::easy: return "easy";
    case CaseDifficulty::medium: return "medium";
    case CaseDifficulty::hard: return "hard";
  }
  return "easy";
}

CaseDifficulty parse_difficulty(const std::string& word) {
  if (word == "easy") return CaseDifficulty::easy;
  if (word == "medium") return CaseDifficulty::medium;
  if (word == "hard") return CaseDifficulty::hard;
  throw BadInput("difficulty must be easy, medium or hard, got \"" + word + "\"");
}

GeneratedCase generate_case(std::uint64_t seed, CaseDifficulty difficulty) {
  GeneratedCase c;
  c.seed = seed;
  c.difficulty = difficulty;
  c.body = BodyOutline{{80.0, 60.0}, 78.0, 58.0, 6.0};  // the 160 x 120 mm pad, corners blunted
  c.layers = {{"skin", 1.5, 1.2 * kBackground_kPa}, {"tissue", 48.5, kBackground_kPa}};
  c.felt = {kBackground_kPa, kHardReference * kBackground_kPa};

  // The difficulty is mixed into the seed so that "seed 7 easy" and "seed 7 hard" differ.
  CaseRandom rng(seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(difficulty) + 1);
  const Level lv = level_of(difficulty);
  const int count = rng.integer(lv.min_count, lv.max_count);
  for (int n = 0; n < count; ++n) {
    GeneratedTumor t;
    t.name = "T" + std::to_string(n + 1);
    t.lateral_radius_mm = rng.uniform(lv.radius_lo, lv.radius_hi);
    const double r = t.lateral_radius_mm;
    t.stiffness_kPa = kBackground_kPa * rng.uniform(lv.contrast_lo, lv.contrast_hi);
    const double depth = r + rng.uniform(lv.cover_lo, lv.cover_hi);
    // Where: inside the body with a margin, clear of the tumors placed so far.
    bool placed = false;
    for (int attempt = 0; attempt < kPlacementTries && !placed; ++attempt) {
      const double margin = r + 15.0;
      const double x = rng.uniform(c.body.centre.x_mm - c.body.half_width_mm + margin,
                                   c.body.centre.x_mm + c.body.half_width_mm - margin);
      const double y = rng.uniform(c.body.centre.y_mm - c.body.half_height_mm + margin,
                                   c.body.centre.y_mm + c.body.half_height_mm - margin);
      bool clear = true;
      for (const GeneratedTumor& o : c.tumors)
        if (std::hypot(x - o.centre.x_mm, y - o.centre.y_mm) < r + o.lateral_radius_mm + kGap_mm) clear = false;
      if (!clear) continue;
      t.centre = {x, y, depth};
      placed = true;
    }
    if (!placed) break;  // the pad is full: fewer tumors, still reproducible
    switch (difficulty) {
      case CaseDifficulty::easy:
        t.shape = GeneratedTumor::Shape::sphere;
        t.radii_mm = {r, r, r};
        break;
      case CaseDifficulty::medium:
        t.shape = GeneratedTumor::Shape::ellipsoid;
        t.radii_mm = {r, r * rng.uniform(0.7, 1.0), r * rng.uniform(0.6, 1.0)};
        t.yaw_deg = rng.uniform(0.0, 180.0);
        break;
      case CaseDifficulty::hard: {
        // Two or three lobes of radius sigma (k = 1, s = 1/sigma^2, threshold 1/e: a lone lobe
        // is the ball of radius sigma) spread so that the union stays within r of the centre.
        t.shape = GeneratedTumor::Shape::blobs;
        t.threshold = std::exp(-1.0);
        const int lobes = rng.integer(2, 3);
        const double sigma = 0.6 * r;
        const double spread = r - sigma;
        const double turn = rng.uniform(0.0, 2.0 * std::numbers::pi);
        for (int k = 0; k < lobes; ++k) {
          const double a = turn + 2.0 * std::numbers::pi * k / lobes;
          const double s = 1.0 / (sigma * sigma);
          t.lobes.push_back({{t.centre.x_mm + spread * std::cos(a), t.centre.y_mm + spread * std::sin(a),
                              depth + rng.uniform(-0.3, 0.3) * sigma},
                             1.0,
                             {s, s, s}});
        }
        t.radii_mm = {r, r, sigma};
        break;
      }
    }
    c.tumors.push_back(std::move(t));
  }
  return c;
}

FrepShape tumor_shape(const GeneratedTumor& t) {
  FrepShape s;
  switch (t.shape) {
    case GeneratedTumor::Shape::sphere: s.sphere(t.centre, t.radii_mm[0]); break;
    case GeneratedTumor::Shape::ellipsoid: s.ellipsoid(t.centre, t.radii_mm, t.yaw_deg); break;
    case GeneratedTumor::Shape::blobs: s.blobs(t.lobes, t.threshold); break;
  }
  return s;
}

TissueDefinition case_tissue(const GeneratedCase& c) {
  TissueDefinition d;
  d.body = c.body;
  d.layers = c.layers;
  d.felt = c.felt;
  for (const GeneratedTumor& t : c.tumors) {
    Inclusion inc;
    inc.name = t.name;
    inc.kind = InclusionKind::tumor;
    inc.shape = tumor_shape(t);
    inc.stiffness_kPa = t.stiffness_kPa;
    d.inclusions.push_back(std::move(inc));
  }
  return d;
}

}  // namespace palprig
