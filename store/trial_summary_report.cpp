#include "store/trial_summary_report.hpp"

#include "core/input_error.hpp"
#include "store/export_text.hpp"
#include "store/pulse_store.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/threshold_summary.hpp"

#include <cmath>
#include <array>
#include <cstdio>
#include <sstream>

namespace palprig {

namespace {

// Not available: "n/a" in the table (one spelling for the reader), "NA" in the CSV (R's
// read.csv and pandas read it as missing).
constexpr const char* kTableNotAvailable = "n/a";
constexpr const char* kCsvNotAvailable = "NA";
using export_text::fixed;
using export_text::number_or_null;

struct NamedMeasure {
  const char* name;
  const Measure& m;
};

std::array<NamedMeasure, 4> measures_of(const SummaryRow& r) {
  return {{{"Se", r.measures.se}, {"Sp", r.measures.sp}, {"PPV", r.measures.ppv}, {"ACC", r.measures.acc}}};
}
}  // namespace

std::string summary_table(const TrialSummary& s) {
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> header;
  for (SummaryKey k : s.by) header.push_back(to_string(k));
  for (const char* h : {"trials", "no answer", "TP", "FN", "TN", "FP", "Se [95% CI]", "Sp [95% CI]", "PPV [95% CI]",
                        "ACC [95% CI]", "RT mean s", "RT sd s", "RT after stim mean s", "RT after stim sd s"}) {
    header.push_back(h);
  }
  if (s.any_rated) {
    header.push_back("rated");
    header.push_back("confidence mean");
  }
  cells.push_back(header);
  for (const SummaryRow& r : s.rows) {
    std::vector<std::string> line = r.key;
    for (std::int64_t v : {r.trials, r.unanswered, r.counts.tp, r.counts.fn, r.counts.tn, r.counts.fp}) {
      line.push_back(std::to_string(v));
    }
    if (!r.negatives_counted) line[line.size() - 2] = kTableNotAvailable;  // TN
    for (const auto& nm : measures_of(r)) {
      line.push_back(nm.m.defined
                         ? fixed(nm.m.value, 3, kCsvNotAvailable) + " [" + fixed(nm.m.lower, 3, kCsvNotAvailable) +
                               ", " + fixed(nm.m.upper, 3, kCsvNotAvailable) + "]"
                         : std::string(kTableNotAvailable));
    }
    line.push_back(fixed(r.mean_rt_s, 2, kTableNotAvailable));
    line.push_back(fixed(r.sd_rt_s, 2, kTableNotAvailable));
    line.push_back(fixed(r.mean_rt_after_stimulus_s, 2, kTableNotAvailable));
    line.push_back(fixed(r.sd_rt_after_stimulus_s, 2, kTableNotAvailable));
    if (s.any_rated) {
      line.push_back(std::to_string(r.rated));
      line.push_back(fixed(r.mean_confidence, 2, kTableNotAvailable));
    }
    cells.push_back(line);
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& line : cells) {
    for (std::size_t i = 0; i < line.size(); ++i) width[i] = std::max(width[i], line[i].size());
  }
  std::ostringstream out;
  for (const auto& line : cells) {
    for (std::size_t i = 0; i < line.size(); ++i) {
      out << line[i] << (i + 1 < line.size() ? std::string(width[i] - line[i].size() + 2, ' ') : "");
    }
    out << "\n";
  }
  return out.str();
}

std::string summary_csv(const TrialSummary& s) {
  std::ostringstream out;
  for (SummaryKey k : s.by) out << to_string(k) << ",";
  out << "trials,unanswered,TP,FN,TN,FP";
  for (const char* m : {"Se", "Sp", "PPV", "ACC"}) out << "," << m << "," << m << "_lower," << m << "_upper";
  out << ",rt_mean_s,rt_sd_s,rt_after_stimulus_mean_s,rt_after_stimulus_sd_s";
  if (s.any_rated) out << ",rated,confidence_mean";
  out << ",rt_from_reached_mean_s,rt_from_reached_sd_s";  // last: the earlier columns keep their places
  out << "\n";
  for (const SummaryRow& r : s.rows) {
    for (const auto& k : r.key) out << export_text::csv_field(k) << ",";
    out << r.trials << "," << r.unanswered << "," << r.counts.tp << "," << r.counts.fn << ","
        << (r.negatives_counted ? std::to_string(r.counts.tn) : std::string("NA")) << "," << r.counts.fp;
    for (const auto& nm : measures_of(r)) {
      if (nm.m.defined)
        out << "," << fixed(nm.m.value, 6, kCsvNotAvailable) << "," << fixed(nm.m.lower, 6, kCsvNotAvailable) << ","
            << fixed(nm.m.upper, 6, kCsvNotAvailable);
      else
        out << ",NA,NA,NA";
    }
    out << "," << fixed(r.mean_rt_s, 4, kCsvNotAvailable) << "," << fixed(r.sd_rt_s, 4, kCsvNotAvailable) << ","
        << fixed(r.mean_rt_after_stimulus_s, 4, kCsvNotAvailable) << ","
        << fixed(r.sd_rt_after_stimulus_s, 4, kCsvNotAvailable);
    if (s.any_rated) out << "," << r.rated << "," << fixed(r.mean_confidence, 4, kCsvNotAvailable);
    out << "," << fixed(r.mean_rt_from_reached_s, 4, kCsvNotAvailable) << ","
        << fixed(r.sd_rt_from_reached_s, 4, kCsvNotAvailable);
    out << "\n";
  }
  return out.str();
}

nlohmann::ordered_json summary_json(const TrialSummary& s, double confidence, ResponseTimeTest test) {
  nlohmann::ordered_json j;
  j["task"] = "discrimination/localisation";
  j["convention"] =
      "per finger value (discrimination) or per tumor (localisation): Se = TP/(TP+FN), "
      "Sp = TN/(TN+FP), PPV = TP/(TP+FP), ACC = (TP+TN)/all (paper 002 eq. 5-8); localisation: FP per false "
      "mark, TN per normal case left unmarked, Sp = TN/normal cases, ACC n/a; Wilson score "
      "intervals without continuity correction";
  j["confidence"] = confidence;
  j["by"] = nlohmann::ordered_json::array();
  for (SummaryKey k : s.by) j["by"].push_back(to_string(k));
  j["rows"] = nlohmann::ordered_json::array();
  for (const SummaryRow& r : s.rows) {
    nlohmann::ordered_json row;
    for (std::size_t i = 0; i < s.by.size(); ++i) row[to_string(s.by[i])] = r.key[i];
    row["trials"] = r.trials;
    row["unanswered"] = r.unanswered;
    row["TP"] = r.counts.tp;
    row["FN"] = r.counts.fn;
    row["TN"] = r.negatives_counted ? nlohmann::ordered_json(r.counts.tn) : nlohmann::ordered_json(nullptr);
    row["FP"] = r.counts.fp;
    for (const auto& nm : measures_of(r)) {
      if (nm.m.defined) {
        row[nm.name] = {
            {"k", nm.m.k}, {"n", nm.m.n}, {"value", nm.m.value}, {"lower", nm.m.lower}, {"upper", nm.m.upper}};
      } else {
        row[nm.name] = nullptr;
      }
    }
    row["rt_mean_s"] = number_or_null(r.mean_rt_s);
    row["rt_sd_s"] = number_or_null(r.sd_rt_s);
    row["rt_n"] = r.rt_count;
    // From the end of the stimulus; rt_mean_s above is from onset (paper 002's t-test).
    row["rt_after_stimulus_mean_s"] = number_or_null(r.mean_rt_after_stimulus_s);
    row["rt_after_stimulus_sd_s"] = number_or_null(r.sd_rt_after_stimulus_s);
    // From when the stimulus reached the fingers (the monitor at half the commanded level).
    row["rt_from_reached_mean_s"] = number_or_null(r.mean_rt_from_reached_s);
    row["rt_from_reached_sd_s"] = number_or_null(r.sd_rt_from_reached_s);
    if (s.any_rated) {
      row["rated"] = r.rated;
      row["confidence_mean"] = number_or_null(r.mean_confidence);
    }
    j["rows"].push_back(std::move(row));
  }
  const ConditionComparisons between = compare_conditions(s, confidence, test);
  if (between.by_condition) j["comparisons"] = comparisons_json(between);
  return j;
}

std::string stats_trials_text(TrialStore& store, const SummaryOptions& options, const std::string& format,
                              ResponseTimeTest test) {
  const bool json = format == "json";
  std::vector<std::string> parts;               // table and csv: each kind's text
  std::vector<nlohmann::ordered_json> objects;  // json: each kind's object
  bool scored_trials = true;                    // discrimination or localisation trials (a server: assumed)
  if (auto* sqlite = dynamic_cast<SqliteTrialStore*>(&store)) {
    // Pulse-localisation and threshold trials have their own tables (SQLite files only so far).
    PulseStore pulse(*sqlite, false);
    if (pulse.has_trials()) {
      const auto rows = pulse.summarise(options.confidence);
      if (json)
        objects.push_back(pulse_summary_json(rows, options.confidence));
      else
        parts.push_back(pulse_summary_table(rows, options.confidence));
    }
    const auto tracks = summarise_threshold_tracks(*sqlite);
    if (!tracks.empty()) {
      if (json)
        objects.push_back(threshold_summary_json(tracks));
      else
        parts.push_back(threshold_summary_table(tracks));
    }
    auto any = sqlite->database().prepare("SELECT count(*) FROM trials");
    scored_trials = any.step() && any.integer(0) > 0;
    if (!scored_trials && parts.empty() && objects.empty())
      throw InputError(store.location(), "trials", "a store holding trials (it holds none yet)");
  }
  if (scored_trials) {
    const TrialSummary summary = summarise_trials(store, options);
    if (json) {
      objects.push_back(summary_json(summary, options.confidence, test));
    } else if (format == "csv") {
      parts.push_back(summary_csv(summary));
    } else {
      parts.push_back(summary_table(summary) +
                      comparisons_table(compare_conditions(summary, options.confidence, test)));
    }
  }
  if (json) {
    if (objects.size() == 1) return objects[0].dump(2) + "\n";
    nlohmann::ordered_json all;
    all["tasks"] = objects;
    return all.dump(2) + "\n";
  }
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i > 0 ? "\n" : "") + parts[i];
  return out;
}

}  // namespace palprig
