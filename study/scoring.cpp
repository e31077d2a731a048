#include "study/scoring.hpp"

#include <cmath>

namespace palprig {

const char* to_string(Outcome o) noexcept {
  switch (o) {
    case Outcome::tp: return "TP";
    case Outcome::fn: return "FN";
    case Outcome::tn: return "TN";
    case Outcome::fp: return "FP";
  }
  return "TN";
}

std::optional<Outcome> outcome_from_string(std::string_view text) noexcept {
  if (text == "TP") return Outcome::tp;
  if (text == "FN") return Outcome::fn;
  if (text == "TN") return Outcome::tn;
  if (text == "FP") return Outcome::fp;
  return std::nullopt;
}

std::array<Outcome, kFingerCount> score_discrimination(const FingerFlags& truth, const FingerFlags& answer) noexcept {
  std::array<Outcome, kFingerCount> out{};
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    if (truth[f])
      out[f] = answer[f] ? Outcome::tp : Outcome::fn;
    else
      out[f] = answer[f] ? Outcome::fp : Outcome::tn;
  }
  return out;
}

LocalisationScore score_localisation(const std::vector<TumorTruth>& tumors, const std::vector<Mark>& marks,
                                     double tolerance_mm) {
  LocalisationScore score;
  for (const auto& t : tumors) score.tumors.push_back({t.name, false, -1.0});
  for (const Mark& m : marks) {
    int nearest_hit = -1;
    double nearest_hit_mm = 0;
    for (std::size_t i = 0; i < tumors.size(); ++i) {
      const double d = std::hypot(m.x_mm - tumors[i].x_mm, m.y_mm - tumors[i].y_mm);
      TumorScore& ts = score.tumors[i];
      if (ts.nearest_mark_mm < 0 || d < ts.nearest_mark_mm) ts.nearest_mark_mm = d;
      if (d <= tumors[i].radius_mm + tolerance_mm) {
        ts.hit = true;
        if (nearest_hit < 0 || d < nearest_hit_mm) {
          nearest_hit = static_cast<int>(i);
          nearest_hit_mm = d;
        }
      }
    }
    score.mark_tumor.push_back(nearest_hit);
    if (nearest_hit < 0) ++score.false_marks;
  }
  return score;
}

}  // namespace palprig
