#pragma once
// The per-region table of `palprig demo` and `palprig run --regions`: for each tumor of the
// scene, and for soft tissue (more than a margin away from every tumor), the pressure of the
// fingers that pressed over it: target (what the models asked) and plant (the regulator's
// monitor). Each finger counts where it was (the record's finger positions: the pen's
// triangle, or each tracked fingertip), while it pressed (in contact, not vented, its own
// force at least the contact force).
#include <iosfwd>
#include <vector>

#include <nlohmann/json.hpp>

#include "controller/loop_runner.hpp"
#include "formats/scene_description.hpp"

namespace palprig {

class RegionTable final : public TickObserver {
 public:
  RegionTable(const std::vector<TumorTruth>& tumors, double contact_force_N, double soft_margin_mm = 8.0);

  void on_tick(const TelemetryRecord& r) noexcept override;

  struct Row {
    std::uint64_t n = 0;
    double target_sum = 0, target_max = 0, plant_sum = 0, plant_max = 0;
    void add(double target, double plant) noexcept;
    double target_mean() const { return n ? target_sum / double(n) : 0; }
    double plant_mean() const { return n ? plant_sum / double(n) : 0; }
  };
  // One row per tumor, in the scene's order, then soft tissue.
  const std::vector<Row>& rows() const { return rows_; }
  // Every tumor's target and plant means above soft tissue's, and soft tissue touched.
  bool tumors_feel_harder() const;
  void print(std::ostream& out) const;
  nlohmann::json json() const;

 private:
  std::vector<TumorTruth> tumors_;
  double contact_force_N_, margin_mm_;
  std::vector<Row> rows_;
};

}  // namespace palprig
