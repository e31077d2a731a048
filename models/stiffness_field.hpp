#pragma once
// StiffnessField: what one fingertip feels on a function-based tissue block (papers 001, 000).
//
// The tissue: a body whose outline on the skin plane is a super-ellipse (the super-elliptic
// cylinder of paper 001), layers stacked from the skin down (skin, fat, muscle, ...; each with
// a thickness and a Young's modulus), a support under the last layer (the table or bone the
// block lies on), and inclusions built from FRep shapes (tumors, organs, ribs, ligaments), each
// with its own modulus. Where inclusions overlap, the later one in the list wins: list an organ
// before the tumor inside it. Inclusions may move with respiration.
//
// What a finger feels. A fingertip (radius R, 8 mm: paper 002's 16 mm fingertip) pressing with
// force F sinks in by delta(F) = delta_ref (F / F_ref)^(2/3), the Hertz law scaled so that the
// reference press gives paper 002's FE indentation (7 mm at 2 N). Its contact radius is
// a = sqrt(R delta). The tissue it loads lies below the contact: on the axis, the vertical
// stress under a uniformly loaded disc falls with depth z as
//     w(z) = 1 - (z/a)^3 / (1 + (z/a)^2)^(3/2)            (Boussinesq),
// which we use as the weight of each depth, down to 4 a (where it has fallen below 9 %). Across
// the contact, the centre stands for the inner disc (r < a/sqrt(2), 65 % of a Hertz load) and
// four points at 0.75 a for the rest. Each sampled point contributes its modulus on a log scale
// between the scene's soft and hard reference moduli,
//     n(E) = clamp((ln E - ln E_soft) / (ln E_hard - ln E_soft), 0, 1),
// and the felt stiffness is the weighted mean of n: 0 on plain soft tissue, 1 over tissue at
// least as hard as E_hard throughout the loaded zone.
//
// So pressing harder loads deeper tissue (a grows with F): a deep small tumor fills little of a
// light press's zone and needs more force to be felt than a shallow large one. The log scale
// follows Weber's law for perceived stiffness and keeps a stiff support from dominating.
//
// Bone and ligaments are different: they are held by the skeleton (a ligament is a cord pulled
// taut between bones), so the finger presses against them rather than into the tissue around
// them (paper 000's constraint plane for a touched layer). An inclusion of kind bone or ligament
// whose top lies at depth z_b is felt with the Boussinesq stress that reaches it from the sunk
// fingertip, n(E) * w(max(z_b - delta, 0) / a): fully once the finger has sunk to it and nearly
// so just below, which makes a rib under the skin hard at any force. The finger is one rigid
// body, so bone under any contact point stops it; a ring point bears with the Hertz pressure
// there (0.66 of the centre's). The finger feels the larger of the two terms.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "models/finger_layout.hpp"
#include "models/frep.hpp"
#include "models/respiration.hpp"
#include "models/scene.hpp"
#include "models/tissue_drag.hpp"

namespace palprig {

inline constexpr std::size_t kMaxLayers = 16;
inline constexpr std::size_t kMaxInclusions = 64;

struct TissueLayer {
  std::string name;
  double thickness_mm = 1.0;
  double stiffness_kPa = 14.7;
  // Stick/slip of the tissue under a finger pressed into this layer (paper 000, section 3.2).
  // A layer without one (drag_given false) takes the nearest layer's above it; none: no drag.
  DragSetting drag{0, 0, 0};
  bool drag_given = false;
};

// Super-ellipse |dx/a|^n + |dy/b|^n <= 1 on the skin plane.
struct BodyOutline {
  Point2_mm centre;
  double half_width_mm = 80, half_height_mm = 60;
  double exponent = 6.0;  // 001: flat with blunt corners
  bool contains(const Point2_mm& p) const noexcept;
};

enum class InclusionKind : std::uint8_t { tumor, organ, bone, ligament, other };
const char* to_string(InclusionKind k) noexcept;

struct Inclusion {
  std::string name;
  InclusionKind kind = InclusionKind::tumor;
  FrepShape shape;
  double stiffness_kPa = 21.9;
  Point3_mm breathing_excursion_mm;  // displacement at full inspiration; zero: does not move
};

// Moduli that map to felt stiffness 0 and 1 (log scale in between).
struct FeltRange {
  double soft_kPa = 14.7;
  double hard_kPa = 21.9;
};

struct PressModel {
  double finger_radius_mm = 8.0;          // half of paper 002's 16 mm fingertip
  double reference_force_N = 2.0;         // the press of paper 002's FE study...
  double reference_indentation_mm = 7.0;  // ...sinks 7 mm
  double min_contact_radius_mm = 1.0;     // a barely touching finger still feels its contact patch

  double indentation_mm(double force_N) const noexcept;
  double contact_radius_mm(double force_N) const noexcept;
  double reach_mm(double force_N) const noexcept;  // depth of the loaded zone: 4 a
};

struct TissueDefinition {
  BodyOutline body;
  std::vector<TissueLayer> layers;  // from the skin down; at least one
  double support_kPa = 0;           // under the last layer; 0: the last layer continues
  std::vector<Inclusion> inclusions;
  Respiration respiration;
  FeltRange felt;
  PressModel press;
};

class StiffnessField {
 public:
  // Throws BadInput for a definition that cannot describe tissue (no layers,
  // non-positive sizes or moduli, soft >= hard, too many layers or inclusions).
  explicit StiffnessField(TissueDefinition definition);

  // Young's modulus at a point (kPa); 0 outside the body outline (air).
  double modulus_kPa(const Point3_mm& p, double t_s) const noexcept;
  // Felt stiffness 0..1 at a finger centre for a pressing force, and the layer pressed into.
  TissueSample sample(const Point2_mm& at, double force_N, double t_s) const noexcept;
  double felt_stiffness(const Point2_mm& at, double force_N, double t_s) const noexcept {
    return sample(at, force_N, t_s).stiffness;
  }
  // Index of the layer at a depth (the last layer for depths beyond the stack).
  int layer_at(double depth_mm) const noexcept;
  // The most shape evaluations one sample() can make (FrepShape::worst_case_cost units): the
  // depth and bisection points of its five lateral points, each over the inclusions whose boxes
  // (widened by their breathing excursion) can overlap there. The scene loader refuses a scene
  // whose three fingers cost more than a tick can afford.
  double worst_case_sample_cost() const noexcept;
  double normalised(double modulus_kPa) const noexcept;
  SceneBounds bounds() const noexcept;
  const TissueDefinition& definition() const noexcept { return def_; }

 private:
  // A material's felt value n(E) is constant, so it is computed once per layer and inclusion.
  struct Level {
    double value;
    bool rigid;  // inside a bone or ligament inclusion
  };
  Level level_at(const Point3_mm& p, const std::uint16_t* candidates, std::size_t count,
                 const std::array<Point3_mm, kMaxInclusions>& shift) const noexcept;

  TissueDefinition def_;
  std::array<double, kMaxLayers> layer_bottom_mm_{};
  std::array<double, kMaxLayers> layer_level_{};
  std::array<double, kMaxInclusions> inclusion_level_{};
  std::array<bool, kMaxInclusions> inclusion_rigid_{};
  std::array<Box3_mm, kMaxInclusions> inclusion_box_{};
  double support_level_ = 0;
  double log_soft_ = 0, inv_log_span_ = 1;
  bool any_breathing_ = false;
};

}  // namespace palprig
