#pragma once
// FunctionScene: a function-based tissue block (StiffnessField: body, layers, FRep inclusions,
// respiration) with its arteries (PulseField), behind the Scene interface the tick samples.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "models/artery.hpp"
#include "models/fe_stress_table.hpp"
#include "models/scene.hpp"
#include "models/stiffness_field.hpp"

namespace palprig {

// Where an inclusion is, as a trainee's answer is scored: its outline on the skin plane (the
// circle around its bounding box), and its depth.
struct InclusionOutline {
  std::string name;
  InclusionKind kind = InclusionKind::tumor;
  double x_mm = 0, y_mm = 0, radius_mm = 0;
  double top_depth_mm = 0, bottom_depth_mm = 0;
  double stiffness_kPa = 0;
};

class FunctionScene final : public Scene {
 public:
  // Throws BadInput for a tissue or an artery that cannot exist.
  FunctionScene(TissueDefinition tissue, std::vector<ArterySpec> arteries);

  TissueSample sample(const Point2_mm& at, double force_N, double t_s) const noexcept override;
  SceneBounds bounds() const noexcept override { return field_.bounds(); }
  const PulseField* pulse() const noexcept override { return arteries_.empty() ? nullptr : &arteries_; }
  DragSetting drag(int layer) const noexcept override;

  const StiffnessField& field() const noexcept { return field_; }
  const PulseField& arteries() const noexcept { return arteries_; }
  // The inclusions of one kind (tumors for localisation tasks), at rest (t = 0).
  std::vector<InclusionOutline> outlines(InclusionKind kind) const;

  // Render from the finite-element table: each tumor is described as the table's nodule (its
  // outline's centre and radius, the depth of its top, its modulus over the layer's around its
  // centre) and sample() adds, on top of the felt stiffness, the stress the nodules add at the
  // finger's press (the largest over the tumors; their rest positions: breathing is not
  // followed). nullptr switches it off.
  void use_fe_table(std::shared_ptr<const FeStressTable> table);
  const FeStressTable* fe_table() const noexcept { return table_.get(); }
  // The stress the tumors add at a finger centre for a pressing force (0 without a table).
  double fe_stress_rise_kPa(const Point2_mm& at, double force_N) const noexcept;

 private:
  struct TableNodule {
    double x_mm, y_mm, cover_mm, diameter_mm, contrast;
  };
  StiffnessField field_;
  PulseField arteries_;
  std::shared_ptr<const FeStressTable> table_;
  std::array<TableNodule, kMaxInclusions> nodules_{};
  std::size_t nodule_count_ = 0;
};

}  // namespace palprig
