#pragma once
// Scene: the virtual tissue the fingers touch. The tick asks it, per finger, what is felt at a
// point for a given pressing force and time. MapScene is paper 002's measured stiffness map;
// function-based phantoms, layers and arteries implement the same interface.
#include <string>

#include "models/finger_layout.hpp"
#include "models/stiffness_map.hpp"
#include "models/tissue_drag.hpp"

namespace palprig {

class PulseField;  // models/artery.hpp

struct TissueSample {
  double stiffness = 0.0;  // normalised 0..1
  int layer = -1;          // index of the layer felt, -1 when the scene has no layers
  // Scenes that render from the finite-element table (function scenes with "fe_stress_table"):
  // the stress the nodules under the finger add to the healthy tissue's at this press, which
  // the tick uses instead of the stiffness rule (controller/tick.cpp).
  bool fe_stress = false;
  double stress_rise_kPa = 0.0;
};

struct SceneBounds {
  double x0_mm = 0, y0_mm = 0, x1_mm = 0, y1_mm = 0;
};

class Scene {
 public:
  virtual ~Scene() = default;
  // Called three times per tick: must not allocate, lock or throw.
  virtual TissueSample sample(const Point2_mm& at, double force_N, double t_s) const noexcept = 0;
  // The region a sweep or a generated case covers.
  virtual SceneBounds bounds() const noexcept = 0;
  // The arteries whose pulse the tick adds to the fingers' pressures; nullptr for a scene
  // without any (a measured map), which the tick then runs exactly as before.
  virtual const PulseField* pulse() const noexcept { return nullptr; }
  // How the tissue drags under a finger pressed into `layer` (TissueSample::layer; -1 before the
  // first sample: the top layer): paper 000's stick/slip. Scenes without layers do not drag.
  // Called per finger per tick: must not allocate, lock or throw.
  virtual DragSetting drag(int /*layer*/) const noexcept { return {0, 0, 0}; }
  // A hint: the tick will sample here soon. A scene that reads a table too large for the cache
  // starts fetching it (the tick asks for every sample of a tick first); the others ignore it.
  // Called per finger per tick: must not allocate, lock or throw.
  virtual void prefetch(const Point2_mm& /*at*/) const noexcept {}
  // Whether prefetch pays: the tick computes where its samples will be twice when it does, which
  // costs more than it saves on a scene that fits in the cache.
  virtual bool prefetch_pays() const noexcept { return false; }
};

class MapScene final : public Scene {
 public:
  MapScene(StiffnessMap map, MapSampling sampling) : map_(std::move(map)), sampling_(sampling) {}
  TissueSample sample(const Point2_mm& at, double, double) const noexcept override {
    return {map_.sample(at.x_mm, at.y_mm, sampling_), -1};
  }
  SceneBounds bounds() const noexcept override { return {0, 0, map_.width_mm(), map_.height_mm()}; }
  void prefetch(const Point2_mm& at) const noexcept override { map_.prefetch(at.x_mm, at.y_mm, sampling_); }
  // A map beyond a typical last-level cache share (4 MiB; the 4096 x 4096 map is 64 MiB, the
  // bundled phantom 76 KiB).
  bool prefetch_pays() const noexcept override { return map_.values().size() * sizeof(float) > (std::size_t{4} << 20); }
  const StiffnessMap& map() const noexcept { return map_; }
  MapSampling sampling() const noexcept { return sampling_; }

 private:
  StiffnessMap map_;
  MapSampling sampling_;
};

}  // namespace palprig
