#pragma once
// The per-region table of `palprig demo` and `palprig run --regions`: for each tumor of the
// scene, and for soft tissue (more than a margin away from every tumor), the pressure of the
// fingers that pressed over it: target (what the models asked) and plant (the regulator's
// monitor). Each finger counts where it was (the record's finger positions: the pen's
// triangle, or each tracked fingertip), while it pressed (in contact, not vented, its own
// force at least the contact force). Only readings there are count: a monitor with no reading
// (a link down) adds nothing to the plant column. After a fault the table says the run faulted
// and covers what ran before it: a region never reached is "not reached", never a 0 or a NaN,
// and no verdict is drawn on tumors the fingers did not get to.
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
    std::uint64_t n = 0;        // finger-ticks with a target
    std::uint64_t plant_n = 0;  // of which with a monitor reading
    double target_sum = 0, target_max = 0, plant_sum = 0, plant_max = 0;
    void add(double target, double plant) noexcept;
    double target_mean() const { return n ? target_sum / double(n) : 0; }
    double plant_mean() const { return plant_n ? plant_sum / double(plant_n) : 0; }
  };
  // One row per tumor, in the scene's order, then soft tissue.
  const std::vector<Row>& rows() const { return rows_; }
  // Every tumor's target and plant means above soft tissue's, and soft tissue touched.
  bool tumors_feel_harder() const;
  // `fault` (empty: the run ended normally) and when it came: the table then covers the run up
  // to it and draws no verdict.
  void print(std::ostream& out, const std::string& fault = "", double fault_t_s = 0) const;
  nlohmann::json json() const;

 private:
  std::vector<TumorTruth> tumors_;
  double contact_force_N_, margin_mm_;
  std::vector<Row> rows_;
};

}  // namespace palprig
