#pragma once
// Scoring of answers, as in paper 002.
//   discrimination  each finger's value is scored on its own: tumor there and answered -> TP,
//                   there but not answered -> FN, absent and not answered -> TN, absent but
//                   answered -> FP; a trial yields 3 values
//   localisation    a tumor is detected (TP) when a mark lies within its outline plus the
//                   protocol's tolerance, else missed (FN); marks near no tumor are false marks
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "formats/scene_file.hpp"
#include "statistics/outcome.hpp"
#include "study/protocol.hpp"

namespace palprig {

const char* to_string(Outcome o) noexcept;  // "TP", "FN", "TN", "FP"
std::optional<Outcome> outcome_from_string(std::string_view text) noexcept;

std::array<Outcome, kFingerCount> score_discrimination(const FingerFlags& truth, const FingerFlags& answer) noexcept;

struct Mark {
  double x_mm = 0, y_mm = 0;
};

struct TumorScore {
  std::string tumor;
  bool hit = false;
  double nearest_mark_mm = -1;  // distance from the tumor's centre to the nearest mark; -1 without marks
};

struct LocalisationScore {
  std::vector<TumorScore> tumors;
  std::vector<int> mark_tumor;  // per mark: index of the nearest tumor it hits, -1 for a false mark
  int false_marks = 0;
};

LocalisationScore score_localisation(const std::vector<TumorTruth>& tumors, const std::vector<Mark>& marks,
                                     double tolerance_mm);

}  // namespace palprig
