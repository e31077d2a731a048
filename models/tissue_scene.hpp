#pragma once
// FunctionScene: a function-based tissue block (StiffnessField: body, layers, FRep inclusions,
// respiration) with its arteries (PulseField), behind the Scene interface the tick samples.
#include <string>
#include <vector>

#include "models/artery.hpp"
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

  TissueSample sample(const Point2_mm& at, double force_N, double t_s) const noexcept override {
    return field_.sample(at, force_N, t_s);
  }
  SceneBounds bounds() const noexcept override { return field_.bounds(); }
  const PulseField* pulse() const noexcept override { return arteries_.empty() ? nullptr : &arteries_; }
  DragSetting drag(int layer) const noexcept override;

  const StiffnessField& field() const noexcept { return field_; }
  const PulseField& arteries() const noexcept { return arteries_; }
  // The inclusions of one kind (tumors for localisation tasks), at rest (t = 0).
  std::vector<InclusionOutline> outlines(InclusionKind kind) const;

 private:
  StiffnessField field_;
  PulseField arteries_;
};

}  // namespace palprig
