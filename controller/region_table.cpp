#include "controller/region_table.hpp"

#include <cmath>
#include <string>
#include <vector>
#include <iomanip>
#include <ostream>

namespace palprig {

void RegionTable::Row::add(double target, double plant) noexcept {
  if (!std::isfinite(target)) return;
  ++n;
  target_sum += target;
  target_max = std::max(target_max, target);
  if (!std::isfinite(plant)) return;  // no reading (a link down): nothing to average
  ++plant_n;
  plant_sum += plant;
  plant_max = std::max(plant_max, plant);
}

RegionTable::RegionTable(const std::vector<TumorTruth>& tumors, double contact_force_N, double soft_margin_mm)
    : tumors_(tumors), contact_force_N_(contact_force_N), margin_mm_(soft_margin_mm), rows_(tumors.size() + 1) {}

void RegionTable::on_tick(const TelemetryRecord& r) noexcept {
  if (!(r.flags & kInContact)) return;
  for (int f = 0; f < kFingerCount; ++f) {
    if (r.finger_vent[f] != FingerVent::none || !(r.finger_force_N[f] >= contact_force_N_)) continue;
    bool near_any = false;
    for (std::size_t t = 0; t < tumors_.size(); ++t) {
      const double d = std::hypot(r.finger_x_mm[f] - tumors_[t].x_mm, r.finger_y_mm[f] - tumors_[t].y_mm);
      if (d <= tumors_[t].radius_mm) rows_[t].add(r.target_kPa[f], r.monitor_kPa[f]);
      if (d <= tumors_[t].radius_mm + margin_mm_) near_any = true;
    }
    if (!near_any) rows_.back().add(r.target_kPa[f], r.monitor_kPa[f]);
  }
}

bool RegionTable::tumors_feel_harder() const {
  const Row& soft = rows_.back();
  bool all = soft.n > 0;
  for (std::size_t t = 0; t < tumors_.size(); ++t)
    all = all && rows_[t].n > 0 && rows_[t].target_mean() > soft.target_mean() &&
          rows_[t].plant_mean() > soft.plant_mean();
  return all;
}

void RegionTable::print(std::ostream& out, const std::string& fault, double fault_t_s) const {
  const auto flags = out.flags();
  const auto precision = out.precision();
  out << std::fixed << std::setprecision(2) << "\n  Pressure per region (fingers over it while they pressed; plant = "
      << "regulator monitor)" << (fault.empty() ? "" : ", up to the fault") << "\n"
      << "  region            finger-ticks   target kPa mean / max   plant kPa mean / max\n";
  std::vector<std::string> unreached;
  for (std::size_t t = 0; t <= tumors_.size(); ++t) {
    const Row& r = rows_[t];
    const std::string name =
        t < tumors_.size() ? "tumor " + tumors_[t].name + " (r " + std::to_string(int(tumors_[t].radius_mm)) + " mm)"
                           : "soft tissue";
    out << "  " << std::left << std::setw(18) << name << std::right << std::setw(12) << r.n << "   ";
    if (r.n == 0) {
      out << "   not reached\n";
      unreached.push_back(t < tumors_.size() ? "tumor " + tumors_[t].name : name);
      continue;
    }
    out << std::setw(9) << r.target_mean() << " / " << std::setw(6) << r.target_max << "       ";
    if (r.plant_n == 0)
      out << "    n/a (no monitor reading)\n";
    else
      out << std::setw(7) << r.plant_mean() << " / " << std::setw(6) << r.plant_max << "\n";
  }
  std::string list;
  for (const auto& u : unreached) list += (list.empty() ? "" : ", ") + u;
  out << "\n  ";
  if (!fault.empty())
    out << "The run faulted at t = " << fault_t_s << " s (" << fault << "): the table covers what ran before it"
        << (unreached.empty() ? "" : "; not reached: " + list) << ". No verdict on the tumors.";
  else if (!unreached.empty())
    out << "WARNING: not pressed on during the run: " << list << "; no comparison for "
        << (unreached.size() == 1 ? "it." : "them.");
  else
    out << (tumors_feel_harder() ? "Every tumor got higher pressure than soft tissue."
                                 : "WARNING: a tumor did not get higher pressure than soft tissue.");
  out << "\n";
  out.flags(flags);
  out.precision(precision);
}

nlohmann::json RegionTable::json() const {
  nlohmann::json regions = nlohmann::json::array();
  for (std::size_t t = 0; t <= tumors_.size(); ++t) {
    const Row& r = rows_[t];
    // JSON has no NaN: a region not reached, or without a monitor reading, has null figures.
    auto figure = [](bool have, double v) { return have ? nlohmann::json(v) : nlohmann::json(nullptr); };
    regions.push_back({{"region", t < tumors_.size() ? "tumor " + tumors_[t].name : "soft tissue"},
                       {"finger_ticks", r.n},
                       {"target_kPa_mean", figure(r.n > 0, r.target_mean())},
                       {"target_kPa_max", figure(r.n > 0, r.target_max)},
                       {"plant_kPa_mean", figure(r.plant_n > 0, r.plant_mean())},
                       {"plant_kPa_max", figure(r.plant_n > 0, r.plant_max)}});
  }
  return regions;
}

}  // namespace palprig
