#pragma once
// Generated rehearsal cases (paper 001's "practically unlimited sets of educational cases"):
// a tissue block like paper 002's phantom with 0..3 tumors whose count, size, depth, shape and
// stiffness contrast follow a difficulty level. The same seed and difficulty always give the
// same case (the random numbers come from std::mt19937_64, whose sequence the C++ standard
// fixes, turned into numbers by this file's own arithmetic rather than the library's
// distributions, which differ between standard libraries).
//
//   level    tumors  lateral radius  centre depth        shape                  contrast E/E_bg
//   easy     1-2     8-12 mm         radius + 1-4 mm     sphere                 2.5-3.5
//   medium   1-3     5-8 mm          radius + 4-10 mm    ellipsoid, turned      1.7-2.5
//   hard     0-3     3-5.5 mm        radius + 8-16 mm    2-3 lobed blob         1.25-1.7
//
// A hard case may hold no tumor at all: telling a normal case from an abnormal one is part of
// the skill (specificity). Tumors keep 12 mm of soft tissue between their outlines and stay
// inside the body outline.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "models/frep.hpp"
#include "models/stiffness_field.hpp"
#include "models/tissue_scene.hpp"

namespace palprig {

enum class CaseDifficulty : std::uint8_t { easy, medium, hard };
const char* to_string(CaseDifficulty d) noexcept;
// Throws BadInput for anything but "easy", "medium", "hard".
CaseDifficulty parse_difficulty(const std::string& word);

struct GeneratedTumor {
  enum class Shape : std::uint8_t { sphere, ellipsoid, blobs } shape = Shape::sphere;
  std::string name;
  Point3_mm centre;
  std::array<double, 3> radii_mm{};  // sphere: all equal; ellipsoid: semi-axes
  double yaw_deg = 0;                // ellipsoid
  std::vector<Blob> lobes;           // blobs
  double threshold = 0;              // blobs
  double lateral_radius_mm = 0;      // what the generator aimed for on the skin plane
  double stiffness_kPa = 0;
};

struct GeneratedCase {
  std::uint64_t seed = 0;
  CaseDifficulty difficulty = CaseDifficulty::easy;
  BodyOutline body;
  std::vector<TissueLayer> layers;
  FeltRange felt;
  std::vector<GeneratedTumor> tumors;
};

GeneratedCase generate_case(std::uint64_t seed, CaseDifficulty difficulty);
// The FRep shape of one generated tumor, and the whole case as a scene.
FrepShape tumor_shape(const GeneratedTumor& t);
TissueDefinition case_tissue(const GeneratedCase& c);

}  // namespace palprig
