#include "store/threshold_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "store/export_text.hpp"
#include "store/threshold_export.hpp"

namespace palprig {

namespace {

using export_text::fixed;
using export_text::number_or_null;

}  // namespace

std::vector<ThresholdTrackSummary> summarise_threshold_tracks(SqliteTrialStore& store) {
  std::vector<ThresholdTrackSummary> out;
  // (session, track) -> its row, in the export's order (the store's sessions, then position).
  std::map<std::pair<std::int64_t, int>, std::size_t> index;
  for (const ThresholdExportRow& r : threshold_export_rows(store, store.list_sessions())) {
    const auto key = std::make_pair(r.session, r.trial.track);
    auto it = index.find(key);
    if (it == index.end()) {
      ThresholdTrackSummary s;
      s.participant = r.participant.code;
      s.session = r.session;
      s.track = r.trial.track_name;
      s.fingers = r.trial.fingers;
      s.procedure = r.procedure;
      s.method = r.method;
      it = index.emplace(key, out.size()).first;
      out.push_back(std::move(s));
    }
    ThresholdTrackSummary& s = out[it->second];
    ++s.trials;
    if (r.trial.answered) ++s.answered;
    if (r.trial.answered && r.trial.correct) ++s.correct;
    s.estimate = r.estimate;  // the estimate after the track's latest trial
    s.finished = r.track_finished;
  }
  return out;
}

std::string threshold_summary_table(const std::vector<ThresholdTrackSummary>& rows) {
  std::vector<std::vector<std::string>> cells{{"participant", "session", "track", "fingers", "procedure", "trials",
                                               "correct", "reversals", "threshold kPa", "at % correct", "sd",
                                               "finished"}};
  for (const ThresholdTrackSummary& r : rows) {
    const bool staircase = r.procedure == "staircase";
    cells.push_back(
        {r.participant, std::to_string(r.session), r.track, r.fingers, r.procedure,
         std::to_string(r.trials) +
             (r.answered < r.trials ? " (" + std::to_string(r.trials - r.answered) + " unanswered)" : std::string()),
         r.answered > 0 ? fixed(100.0 * r.correct / r.answered, 1) + " %" : std::string("n/a"),
         staircase ? std::to_string(r.estimate.reversals) : std::string("n/a"), fixed(r.estimate.threshold_kPa, 3),
         fixed(100.0 * r.estimate.target_probability, 1), fixed(r.estimate.sd, 3) + (staircase ? " kPa" : " log10"),
         r.finished ? "yes" : "no"});
  }
  std::vector<std::size_t> width(cells[0].size(), 0);
  for (const auto& line : cells)
    for (std::size_t i = 0; i < line.size(); ++i) width[i] = std::max(width[i], line[i].size());
  std::string out =
      "Thresholds (each track's own estimate: a staircase's mean of its last reversals, QUEST's posterior mean; at "
      "the proportion correct its rule converges to; fits: palprig stats psychometric)\n";
  for (const auto& line : cells) {
    for (std::size_t i = 0; i < line.size(); ++i)
      out += line[i] + (i + 1 < line.size() ? std::string(width[i] - line[i].size() + 2, ' ') : "");
    out += "\n";
  }
  return out;
}

nlohmann::ordered_json threshold_summary_json(const std::vector<ThresholdTrackSummary>& rows) {
  nlohmann::ordered_json j;
  j["task"] = "threshold";
  j["convention"] =
      "per session and adaptive track: the track's own threshold estimate (staircase: mean of its last reversals; "
      "QUEST: posterior mean) at target_probability, the proportion correct its rule converges to (1-up 3-down: "
      "0.794); sd: of the averaged reversals in kPa (staircase) or the posterior's in log10 units (QUEST)";
  j["tracks"] = nlohmann::ordered_json::array();
  for (const ThresholdTrackSummary& r : rows) {
    nlohmann::ordered_json t;
    t["participant"] = r.participant;
    t["session"] = r.session;
    t["track"] = r.track;
    t["fingers"] = r.fingers;
    t["procedure"] = r.procedure;
    t["method"] = r.method;
    t["trials"] = r.trials;
    t["answered"] = r.answered;
    t["correct"] = r.correct;
    t["reversals"] = r.procedure == "staircase" ? nlohmann::ordered_json(r.estimate.reversals) : nullptr;
    t["threshold_kPa"] = number_or_null(r.estimate.threshold_kPa);
    t["target_probability"] = r.estimate.target_probability;
    t["sd"] = number_or_null(r.estimate.sd);
    t["ci_low_kPa"] = number_or_null(r.estimate.ci_low_kPa);
    t["ci_high_kPa"] = number_or_null(r.estimate.ci_high_kPa);
    t["finished"] = r.finished;
    j["tracks"].push_back(std::move(t));
  }
  return j;
}

}  // namespace palprig
