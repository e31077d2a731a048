#pragma once
// `palprig export --plot DIR`: the figures of every task kind a store holds, as PNG (and SVG
// beside it with --svg):
//   discrimination / localisation  measures_by_condition: Se, Sp, PPV, ACC per condition with
//                                  Wilson intervals (paper 002 fig. 15); measures_by_finger
//                                  (discrimination: per finger value); sensitivity_by_tumor
//                                  (localisation)
//   threshold                      track_session<N>: every track's levels with its reversals;
//                                  psychometric_<track>: the answers per level with the fitted
//                                  curve, threshold and its bootstrap interval
//   pulse localisation             pulse_hits_by_condition: hit rate per condition with Wilson
//                                  intervals and n; pulse_distance_by_condition: the mark's
//                                  distance to the artery (median, quartiles)
// Practice trials are left out, as `stats trials` leaves them out.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "store/trial_store.hpp"

namespace palprig::charts {

struct StorePlotOptions {
  bool svg = false;     // an SVG beside every PNG
  int bootstrap = 200;  // resamples of each psychometric fit's interval
  std::uint64_t seed = 1;
};

// Returns the files written. InputError when the store holds nothing to plot.
std::vector<std::filesystem::path> plot_store(TrialStore& store, const std::filesystem::path& dir,
                                              const StorePlotOptions& options);

}  // namespace palprig::charts
