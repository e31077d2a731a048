#include "study/threshold_protocol.hpp"

#include <algorithm>
#include <set>

#include "formats/json_file.hpp"
#include "models/finger_layout.hpp"
#include "core/input_error.hpp"
#include "study/session_bounds.hpp"

namespace palprig {

const char* to_string(ThresholdMethod m) noexcept { return m == ThresholdMethod::two_afc ? "2afc" : "yes-no"; }

bool is_threshold_protocol(const nlohmann::json& document) {
  return document.is_object() && document.contains("task") && document["task"] == "threshold";
}

namespace {

constexpr double kMaxKPa = 100.0;

StaircaseSettings read_staircase(const JsonObject& o) {
  StaircaseSettings s;
  s.up = static_cast<int>(o.integer_or("up", 1, 1, 10));
  s.down = static_cast<int>(o.integer_or("down", 3, 1, 10));
  s.min_kPa = o.number_or("min_kPa", 0.0, 0.0, kMaxKPa);
  s.max_kPa = o.number("max_kPa", 0.0, kMaxKPa);
  if (!(s.max_kPa > s.min_kPa)) o.fail("max_kPa", "a level above min_kPa");
  s.start_kPa = o.number("start_kPa", s.min_kPa, s.max_kPa);
  s.step_up_kPa = o.number("step_up_kPa", 1e-3, kMaxKPa);
  s.step_down_kPa = o.number_or("step_down_kPa", s.step_up_kPa, 1e-3, kMaxKPa);
  s.min_step_kPa = o.number_or("min_step_kPa", std::min(s.step_up_kPa, s.step_down_kPa) / 8, 1e-4, kMaxKPa);
  s.halve_at_reversals.clear();
  if (o.has("halve_at_reversals")) {
    for (double r : o.numbers("halve_at_reversals", 1, 1000)) {
      if (r != static_cast<int>(r)) o.fail("halve_at_reversals", "whole reversal counts such as [2, 4]");
      s.halve_at_reversals.push_back(static_cast<int>(r));
    }
  }
  s.stop_reversals = static_cast<int>(o.integer_or("stop_reversals", 12, 1, 1000));
  s.max_trials = static_cast<int>(o.integer_or("max_trials", 120, 1, kMaxSessionTrials));
  s.threshold_reversals = static_cast<int>(o.integer_or("threshold_reversals", 8, 1, 1000));
  if (s.threshold_reversals > s.stop_reversals) {
    o.fail("threshold_reversals", "at most stop_reversals (" + std::to_string(s.stop_reversals) + ")");
  }
  o.refuse_unknown();
  return s;
}

QuestSettings read_quest(const JsonObject& o, ThresholdMethod method) {
  QuestSettings q;
  q.min_kPa = o.number_or("min_kPa", 0.05, 1e-3, kMaxKPa);
  q.max_kPa = o.number("max_kPa", 1e-3, kMaxKPa);
  if (!(q.max_kPa > q.min_kPa)) o.fail("max_kPa", "a level above min_kPa");
  q.prior_threshold_kPa = o.number("prior_threshold_kPa", q.min_kPa, q.max_kPa);
  q.prior_sd_log10 = o.number_or("prior_sd_log10", 0.5, 0.01, 5.0);
  q.grid_step_log10 = o.number_or("grid_step_log10", 0.005, 1e-4, 0.5);
  q.grid_half_width_log10 = o.number_or("grid_half_width_log10", 1.5, 0.05, 5.0);
  q.beta = o.number_or("beta", 1.4, 0.05, 50.0);
  q.delta = o.number_or("delta", 0.01, 0.0, 0.2);
  q.gamma = o.number_or("gamma", method == ThresholdMethod::two_afc ? 0.5 : 0.0, 0.0, 0.9);
  q.p_threshold = o.number_or("p_threshold", method == ThresholdMethod::two_afc ? 0.82 : 0.5, 0.01, 0.99);
  if (!(q.p_threshold > q.gamma && q.p_threshold < 1 - q.delta)) {
    o.fail("p_threshold", "a proportion between gamma and 1 - delta");
  }
  q.placement = o.choice_or("placement", "mean", {"mean", "mode"}) == "mode" ? QuestSettings::Placement::mode
                                                                             : QuestSettings::Placement::mean;
  q.max_trials = static_cast<int>(o.integer_or("max_trials", 60, 1, kMaxSessionTrials));
  q.stop_sd_log10 = o.number_or("stop_sd_log10", 0.0, 0.0, 5.0);
  o.refuse_unknown();
  return q;
}

double track_max_kPa(const TrackSpec& t) {
  return t.procedure == AdaptiveProcedure::staircase ? t.staircase.max_kPa : t.quest.max_kPa;
}

}  // namespace

double ThresholdProtocol::max_pressure_kPa() const {
  double m = 0;
  for (const TrackSpec& t : tracks) m = std::max(m, track_max_kPa(t));
  return reference_kPa + m;
}

ThresholdProtocol parse_threshold_protocol(const nlohmann::json& document, const std::string& source) {
  const JsonObject root(document, source, "");
  root.require_version(1);
  ThresholdProtocol p;
  p.source = source;
  p.snapshot = document;
  p.name = root.string("name");
  if (p.name.empty()) root.fail("name", "a non-empty protocol name");
  root.choice("task", {"threshold"});
  p.description = root.string_or("description", "");
  p.bids_task = root.string_or("bids_task", "threshold");
  for (char c : p.bids_task) {
    if (!std::isalnum(static_cast<unsigned char>(c))) root.fail("bids_task", "letters and digits only");
  }
  const JsonObject t = root.object("threshold");
  p.method = t.choice("method", {"2afc", "yes-no"}) == "2afc" ? ThresholdMethod::two_afc : ThresholdMethod::yes_no;
  p.reference_kPa = t.number("reference_kPa", 0.0, kMaxKPa);
  p.timing.interval_s = t.number_or("interval_s", 1.0, 0.05, 60.0);
  p.timing.gap_s = t.number_or("gap_s", 0.5, 0.0, 60.0);
  p.timing.response_timeout_s = t.number_or("response_timeout_s", 10.0, 0.1, 3600.0);
  p.timing.inter_trial_s = t.number_or("inter_trial_s", 1.0, 0.0, 600.0);
  t.refuse_unknown();

  const auto tracks = root.objects("tracks");
  if (tracks.empty()) root.fail("tracks", "at least one track (a staircase or QUEST)");
  std::set<std::string> names;
  for (const JsonObject& o : tracks) {
    TrackSpec spec;
    spec.name = o.string("name");
    if (spec.name.empty() || !names.insert(spec.name).second) o.fail("name", "a non-empty name used by one track only");
    spec.fingers = o.choice("fingers", {"one", "three"}) == "one" ? FingerSet::one : FingerSet::three;
    spec.finger = static_cast<int>(o.integer_or("finger", 1, 1, kFingerCount)) - 1;
    const std::string procedure = o.choice("procedure", {"staircase", "quest"});
    if (procedure == "staircase") {
      spec.procedure = AdaptiveProcedure::staircase;
      spec.staircase = read_staircase(o.object("staircase"));
    } else {
      spec.procedure = AdaptiveProcedure::quest;
      spec.quest = read_quest(o.object("quest"), p.method);
    }
    o.refuse_unknown();
    p.tracks.push_back(spec);
  }
  long long most_trials = 0;  // every track run to its max_trials (unanswered trials are repeated on top)
  for (const TrackSpec& track : p.tracks) {
    most_trials +=
        track.procedure == AdaptiveProcedure::staircase ? track.staircase.max_trials : track.quest.max_trials;
  }
  if (most_trials > kMaxSessionTrials) root.fail("tracks", "max_trials summing to " + session_bound_text(most_trials));
  root.refuse_unknown();
  if (p.max_pressure_kPa() > kMaxKPa) {
    root.fail("threshold.reference_kPa",
              "reference + the largest track level at most 100 kPa, got " + std::to_string(p.max_pressure_kPa()));
  }
  return p;
}

ThresholdProtocol load_threshold_protocol(const std::filesystem::path& path) {
  return parse_threshold_protocol(read_json_file(path), path.string());
}

}  // namespace palprig
