#include "store/trial_export.hpp"
// About 400 lines: the long CSV and the BIDS discrimination/localisation runs read the same
// ExportTrial rows and write the same columns in two layouts; threshold and pulse rows have
// their own files (threshold_export, pulse_export).

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"
#include "store/export_file.hpp"
#include "store/export_text.hpp"
#include "store/pulse_export.hpp"
#include "store/sqlite_trial_store.hpp"
#include "store/threshold_export.hpp"
#include "store/trials_csv.hpp"

namespace palprig {

using namespace export_text;  // number, csv_field, tsv_field, column

namespace {

// One trial as exported: the stored trial with its protocol's finger names.
struct ExportTrial : StoredTrial {
  std::array<std::string, kFingerCount> finger_names{"finger1", "finger2", "finger3"};
  nlohmann::json confidence_scale;  // the protocol's "confidence" object; null when not asked
};

// The finger names of a session's stored protocol, by the protocol file's rules (absent:
// finger1..3). A snapshot that no longer reads is refused rather than exported under made-up
// names: the database was damaged or edited, and the analyst must know.
std::array<std::string, kFingerCount> stored_finger_names(const std::string& file, std::int64_t session,
                                                          const nlohmann::json& protocol) {
  const std::string where = "sessions.protocol_json of session " + std::to_string(session);
  if (protocol.is_discarded() || !protocol.is_object()) {
    throw InputError(file, where,
                     "the protocol stored when the session started, as a JSON object (it no longer "
                     "parses: the database was damaged or edited)");
  }
  std::array<std::string, kFingerCount> names{"finger1", "finger2", "finger3"};
  const auto fingers = protocol.find("fingers");
  if (fingers == protocol.end()) return names;
  if (!fingers->is_array() || fingers->size() != kFingerCount) {
    throw InputError(file, where + ": fingers", "an array of " + std::to_string(kFingerCount) + " finger names");
  }
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    const auto& name = (*fingers)[f];
    if (!name.is_string() || name.get<std::string>().empty()) {
      throw InputError(file, where + ": fingers[" + std::to_string(f) + "]", "a non-empty finger name");
    }
    names[f] = name.get<std::string>();
  }
  return names;
}

std::vector<ExportTrial> read_trials(TrialStore& store, const std::vector<SessionOverview>& sessions,
                                     const ExportOptions& options) {
  std::map<std::int64_t, std::array<std::string, kFingerCount>> finger_names;  // per session, from the protocol
  std::map<std::int64_t, nlohmann::json> confidence_scales;
  for (const SessionOverview& session : sessions) {
    if (session.task != "discrimination" && session.task != "localisation") continue;  // their own tables
    const nlohmann::json protocol = store.protocol_snapshot(session.id);
    finger_names[session.id] = stored_finger_names(store.location(), session.id, protocol);
    const auto scale = protocol.find("confidence");  // checked when the session started
    if (scale != protocol.end() && scale->is_object()) confidence_scales[session.id] = *scale;
  }
  std::vector<ExportTrial> trials;
  for (StoredTrial& stored : store.read_trials(options.include_practice)) {
    ExportTrial t;
    static_cast<StoredTrial&>(t) = std::move(stored);
    t.finger_names = finger_names[t.session];
    if (auto it = confidence_scales.find(t.session); it != confidence_scales.end()) t.confidence_scale = it->second;
    trials.push_back(std::move(t));
  }
  return trials;
}

std::string rating_text(const std::optional<int>& rating, const char* none) {
  return rating ? std::to_string(*rating) : std::string(none);
}

// Every trial of the store, each kind from its own table (threshold and pulse trials live in an
// SQLite store's own tables; the lab's PostgreSQL store holds discrimination and localisation).
struct StoreContents {
  std::vector<SessionOverview> sessions;
  std::vector<ExportTrial> trials;  // discrimination and localisation
  std::vector<ThresholdExportRow> threshold;
  std::vector<PulseExportRow> pulse;
};

StoreContents read_contents(TrialStore& store, const ExportOptions& options) {
  StoreContents c;
  c.sessions = store.list_sessions();
  c.trials = read_trials(store, c.sessions, options);
  if (auto* sqlite = dynamic_cast<SqliteTrialStore*>(&store)) {
    c.threshold = threshold_export_rows(*sqlite, c.sessions);
    c.pulse = pulse_export_rows(*sqlite, c.sessions);
  }
  // Nothing to write is not a success: an analyst must not take an empty folder for the data.
  if (c.trials.empty() && c.threshold.empty() && c.pulse.empty()) {
    bool practice_left_out = false;
    if (!options.include_practice) practice_left_out = !store.read_trials(true).empty();
    throw InputError(store.location(), "trials",
                     practice_left_out
                         ? "trials to export (it holds practice trials only, and --no-practice leaves them out)"
                         : "trials to export (it holds none: no session has committed a trial)");
  }
  return c;
}

void count(ExportResult& r, const StoreContents& c) {
  r.trials = c.trials.size() + c.threshold.size() + c.pulse.size();
  r.threshold_trials = c.threshold.size();
  r.pulse_trials = c.pulse.size();
}

std::string bit(const std::string& flags, int f) {
  if (flags.size() != kFingerCount) return "n/a";
  return std::string(1, flags[static_cast<std::size_t>(f)]);
}

}  // namespace

std::string bids_label_of(const std::string& code) {
  std::string out;
  for (char c : code) {
    if (std::isalnum(static_cast<unsigned char>(c))) out += c;
  }
  return out.empty() ? "unnamed" : out;
}

namespace {

// One BIDS run of discrimination or localisation trials (one session's rows).
void write_trials_run(const std::vector<const ExportTrial*>& rows, const std::string& task,
                      const std::filesystem::path& dir, const std::string& stem,
                      std::vector<std::filesystem::path>& written) {
  const bool localisation = !rows.empty() && rows.front()->mode == "scene";
  std::vector<std::string> tumors;
  for (const ExportTrial* t : rows) {
    for (const auto& [tumor, outcome] : t->tumor_outcomes) {
      if (std::find(tumors.begin(), tumors.end(), tumor) == tumors.end()) tumors.push_back(tumor);
    }
  }

  ExportFile tsv(dir / (stem + "_beh.tsv"));
  nlohmann::ordered_json side;
  side["TaskName"] = task;
  side["TaskDescription"] = rows.empty() ? "" : "palprig protocol " + rows.front()->protocol;
  side["trial"] = column("Position of the trial in the session (1-based, practice included)");
  side["block"] = column("Block number in presentation order (1-based)");
  side["condition"] = column("Condition name from the protocol");
  side["mode"] = column("Presentation mode", "",
                        {{"simultaneous", "all three fingers' pressures at once"},
                         {"sequential", "one finger after the other"},
                         {"scene", "the stiffness map palpated with the pen"}});
  side["practice"] = column("Practice trial, not scored", "", {{"0", "scored trial"}, {"1", "practice trial"}});
  tsv << "trial\tblock\tcondition\tmode\tpractice";
  if (!localisation) {
    tsv << "\tcombination";
    side["combination"] = column("Commanded air pressures of fingers 1/2/3", "kPa");
    for (int f = 1; f <= kFingerCount; ++f) {
      const std::string n = std::to_string(f);
      const std::string name = rows.front()->finger_names[static_cast<std::size_t>(f - 1)];
      tsv << "\tstimulus_finger" << n << "\tfelt_finger" << n << "\ttumor_finger" << n << "\tresponse_finger" << n
          << "\toutcome_finger" << n;
      std::string stimulus = "Air pressure commanded under finger " + n;
      stimulus.append(" (").append(name).append(")");
      side["stimulus_finger" + n] = column(stimulus, "kPa");
      side["felt_finger" + n] =
          column("Mean regulator monitor pressure under finger " + n + " while its stimulus was on", "kPa");
      side["tumor_finger" + n] = column("Ground truth: tumor under finger " + n + " by paper 002's rule", "",
                                        {{"0", "no tumor"}, {"1", "tumor"}});
      side["response_finger" + n] =
          column("Participant answered a tumor under finger " + n, "", {{"0", "no"}, {"1", "yes"}});
      side["outcome_finger" + n] = column(
          "Score of finger " + n + "'s value", "",
          {{"TP", "true positive"}, {"FN", "false negative"}, {"TN", "true negative"}, {"FP", "false positive"}});
    }
  } else {
    for (const auto& tumor : tumors) {
      tsv << "\tdetected_" << tumor;
      side["detected_" + tumor] = column("Tumor " + tumor + " detected: a mark within its outline plus the tolerance",
                                         "", {{"TP", "detected"}, {"FN", "missed"}});
    }
    tsv << "\tfalse_marks\tcase\tcase_tumors";
    side["false_marks"] = column("Marks near no tumor");
    side["case"] = column("The case palpated: a scene's name, or a generated case (case-<difficulty>-<seed>)");
    side["case_tumors"] = column("Tumors in the case (0: a normal case, where no mark is the right answer)");
  }
  tsv << "\tresponse_time\tonset\trt_after_stimulus\tstimulus_reached\trt_from_reached";
  side["response_time"] = column(
      "Time from stimulus onset to the answer (n/a when the response timed out); "
      "paper 002's measure, which includes a sequential presentation",
      "s");
  side["onset"] = column("Stimulus onset on the session's monotonic clock", "s");
  side["rt_after_stimulus"] = column(
      "Time from the end of the stimulus to the answer (0 when answered during the "
      "stimulus; n/a when the response timed out or was not recorded)",
      "s");
  side["stimulus_reached"] = column(
      "When the stimulus reached the fingers on the session's monotonic clock: the first "
      "regulator monitor crossing of half a commanded level (n/a when no finger carried "
      "a level above 0 kPa, for a scene, or when the answer came first)",
      "s");
  side["rt_from_reached"] = column(
      "Time from when the stimulus reached the fingers to the answer (n/a when either is "
      "unknown)",
      "s");
  const nlohmann::json& scale = rows.empty() ? nlohmann::json() : rows.front()->confidence_scale;
  if (!scale.is_null()) {
    tsv << "\tconfidence";
    nlohmann::ordered_json levels;
    const int count = scale.value("levels", 0);
    const auto labels = scale.find("labels");
    for (int level = 1; level <= count; ++level) {
      const bool labelled =
          labels != scale.end() && labels->is_array() && labels->size() == static_cast<std::size_t>(count);
      levels[std::to_string(level)] = labelled ? (*labels)[static_cast<std::size_t>(level - 1)].get<std::string>()
                                               : "rating " + std::to_string(level) + " of " + std::to_string(count);
    }
    side["confidence"] = column("Confidence rating the participant gave after the answer (1 = least, " +
                                    std::to_string(count) + " = most confident; n/a when not answered)",
                                "", levels);
  }
  tsv << "\n";

  for (const ExportTrial* t : rows) {
    tsv << t->position + 1 << "\t" << t->block + 1 << "\t" << tsv_field(t->condition) << "\t" << t->mode << "\t"
        << (t->practice ? 1 : 0);
    if (!localisation) {
      tsv << "\t" << tsv_field(t->combination_label);
      for (int f = 0; f < kFingerCount; ++f) {
        const auto fi = static_cast<std::size_t>(f);
        tsv << "\t" << number(t->stimulus_kPa[fi], 3) << "\t" << number(t->felt_kPa[fi], 3) << "\t" << bit(t->truth, f)
            << "\t" << (t->answered ? bit(t->answer, f) : "n/a") << "\t"
            << (t->outcome[fi].empty() ? "n/a" : t->outcome[fi]);
      }
    } else {
      for (const auto& tumor : tumors) {
        std::string value = "n/a";
        for (const auto& [name, outcome] : t->tumor_outcomes) {
          if (name == tumor) value = outcome;
        }
        tsv << "\t" << value;
      }
      tsv << "\t" << (t->false_marks ? std::to_string(*t->false_marks) : "n/a") << "\t"
          << (t->case_name ? tsv_field(*t->case_name) : std::string("n/a")) << "\t"
          << (t->case_tumors ? std::to_string(*t->case_tumors) : std::string("n/a"));
    }
    tsv << "\t" << number(t->response_time_s) << "\t" << number(t->onset_s) << "\t" << number(t->rt_after_stimulus_s)
        << "\t" << number(t->stimulus_reached_s) << "\t" << number(t->rt_from_reached_s);
    if (!scale.is_null()) tsv << "\t" << rating_text(t->confidence, "n/a");
    tsv << "\n";
  }
  commit_into(tsv, written);
  write_export_json(dir / (stem + "_beh.json"), side, written);
}

}  // namespace

ExportResult export_long_csv(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options) {
  make_export_dir(out_dir);
  const StoreContents c = read_contents(store, options);
  ExportResult result;
  count(result, c);
  if (!c.trials.empty()) {
    const auto long_path = out_dir / "trials_long.csv";
    ExportFile out(long_path);
    out << "participant,simulated,session,protocol,task,trial,block,condition,mode,practice,combination,unit,finger,"
           "finger_name,tumor,stimulus_kPa,felt_kPa,tumor_present,answered,answered_tumor,outcome,response_time_s,"
           "onset_s,completed_utc,rt_after_stimulus_s,confidence,stimulus_reached_s,rt_from_reached_s,case\n";
    for (const ExportTrial& t : c.trials) {
      const std::string head = csv_field(t.participant) + "," + (t.simulated ? "1" : "0") + "," +
                               std::to_string(t.session) + "," + csv_field(t.protocol) + "," + t.task + "," +
                               std::to_string(t.position + 1) + "," + std::to_string(t.block + 1) + "," +
                               csv_field(t.condition) + "," + t.mode + "," + (t.practice ? "1" : "0") + "," +
                               (t.combination_label.empty() ? "n/a" : t.combination_label);
      const std::string tail = std::string(t.answered ? "1" : "0");
      // rt_after_stimulus_s: from the stimulus end (n/a when unanswered or stored before the
      // column existed); confidence: empty when the protocol did not ask or no answer was given;
      // stimulus_reached_s and rt_from_reached_s: n/a when unknown (appended last, so the earlier
      // columns keep their places).
      // case: the localisation case palpated (n/a for discrimination and for trials stored
      // before the column), appended last.
      const std::string times = number(t.response_time_s) + "," + number(t.onset_s) + "," + t.completed_utc + "," +
                                number(t.rt_after_stimulus_s) + "," + rating_text(t.confidence, "") + "," +
                                number(t.stimulus_reached_s) + "," + number(t.rt_from_reached_s) + "," +
                                (t.case_name ? csv_field(*t.case_name) : std::string("n/a"));
      if (t.mode != "scene") {
        for (int f = 0; f < kFingerCount; ++f) {
          const auto fi = static_cast<std::size_t>(f);
          out << head << ",finger" << f + 1 << "," << f + 1 << "," << csv_field(t.finger_names[fi]) << ",n/a,"
              << number(t.stimulus_kPa[fi], 3) << "," << number(t.felt_kPa[fi], 3) << "," << bit(t.truth, f) << ","
              << tail << "," << (t.answered ? bit(t.answer, f) : "n/a") << ","
              << (t.outcome[fi].empty() ? "n/a" : t.outcome[fi]) << "," << times << "\n";
        }
      } else {
        for (const auto& [tumor, outcome] : t.tumor_outcomes) {
          out << head << ",tumor " << csv_field(tumor) << ",n/a,n/a," << csv_field(tumor) << ",n/a,n/a,1," << tail
              << "," << (outcome == "TP" ? "1" : "0") << "," << outcome << "," << times << "\n";
        }
        if (t.case_tumors && *t.case_tumors == 0) {
          // A normal case: one value, TN when left unmarked, FP when marked.
          const bool marked = t.false_marks && *t.false_marks > 0;
          out << head << ",case,n/a,n/a,n/a,n/a,n/a,0," << tail << "," << (t.answered ? (marked ? "1" : "0") : "n/a")
              << "," << (t.answered ? (marked ? "FP" : "TN") : "n/a") << "," << times << "\n";
        } else if (!t.answered || t.tumor_outcomes.empty()) {
          out << head << ",trial,n/a,n/a,n/a,n/a,n/a,n/a," << tail << ",n/a,n/a," << times << "\n";
        }
      }
    }
    commit_into(out, result.files);

    // One row per trial, the unit of a response-time test (store/trials_csv.hpp).
    std::vector<const StoredTrial*> rows;
    for (const ExportTrial& t : c.trials) rows.push_back(&t);
    write_trials_csv(rows, out_dir / "trials.csv", result.files);

    // Marks exist only where the store holds localisation trials (no header-only file).
    const bool localisation =
        std::any_of(c.trials.begin(), c.trials.end(), [](const ExportTrial& t) { return t.mode == "scene"; });
    if (localisation) {
      const auto marks_path = out_dir / "marks.csv";
      ExportFile marks(marks_path);
      marks << "participant,session,trial,mark,x_mm,y_mm,tumor\n";
      for (const ExportTrial& t : c.trials) {  // ordered by participant, session, position; marks by mark
        for (const StoredMark& m : t.marks) {
          marks << csv_field(t.participant) << "," << t.session << "," << t.position + 1 << "," << m.mark + 1 << ","
                << number(m.x_mm, 2) << "," << number(m.y_mm, 2) << "," << (m.tumor ? csv_field(*m.tumor) : "n/a")
                << "\n";
        }
      }
      commit_into(marks, result.files);
    }
  }
  if (!c.threshold.empty()) {
    write_threshold_csv(c.threshold, out_dir / "threshold_trials.csv");
    result.files.push_back(out_dir / "threshold_trials.csv");
  }
  if (!c.pulse.empty()) {
    write_pulse_csv(c.pulse, out_dir / "pulse_trials.csv");
    result.files.push_back(out_dir / "pulse_trials.csv");
  }
  return result;
}

ExportResult export_bids(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options) {
  make_export_dir(out_dir);
  const StoreContents c = read_contents(store, options);
  ExportResult result;
  count(result, c);

  // Participant labels, made unique when two codes reduce to the same letters and digits; in
  // the order participants first appear (discrimination and localisation, then threshold, then
  // pulse trials).
  std::map<std::string, std::string> label_of;
  std::set<std::string> used;
  std::vector<std::pair<std::string, bool>> participants;  // code, simulated
  auto enrol = [&](const std::string& code, int number, bool simulated) {
    if (label_of.count(code)) return;
    std::string label = bids_label_of(code);
    if (used.count(label)) label += "n" + std::to_string(number);
    used.insert(label);
    label_of[code] = label;
    participants.emplace_back(code, simulated);
  };
  for (const ExportTrial& t : c.trials) enrol(t.participant, t.participant_number, t.simulated);
  for (const ThresholdExportRow& r : c.threshold)
    enrol(r.participant.code, r.participant.number, r.participant.simulated);
  for (const PulseExportRow& r : c.pulse) enrol(r.participant.code, r.participant.number, r.participant.simulated);

  // Runs: participant x task, one run per session, whatever the task kind.
  std::map<std::pair<std::string, std::string>, std::vector<std::int64_t>> sessions_of;  // (label, task) -> sessions
  auto add_run = [&](const std::string& code, const std::string& task, std::int64_t session) {
    auto& list = sessions_of[{label_of[code], task}];
    if (std::find(list.begin(), list.end(), session) == list.end()) list.push_back(session);
  };
  std::map<std::int64_t, std::string> bids_task;
  for (const SessionOverview& s : c.sessions) bids_task[s.id] = s.bids_task;
  for (const ExportTrial& t : c.trials) add_run(t.participant, t.bids_task, t.session);
  for (const ThresholdExportRow& r : c.threshold) add_run(r.participant.code, bids_task[r.session], r.session);
  for (const PulseExportRow& r : c.pulse) add_run(r.participant.code, bids_task[r.session], r.session);

  nlohmann::ordered_json description;
  description["Name"] = options.dataset_name.empty() ? "palprig trial export" : options.dataset_name;
  description["BIDSVersion"] = "1.8.0";
  description["DatasetType"] = "raw";
  description["Authors"] =
      options.authors.empty() ? std::vector<std::string>{"Unknown (palprig export --author NAME)"} : options.authors;
  description["GeneratedBy"] = {{{"Name", "palprig"}, {"Description", "palprig export --format bids"}}};
  write_export_json(out_dir / "dataset_description.json", description, result.files);
  {
    // BIDS asks for a README at the top: what the data are and where their columns are described.
    std::set<std::string> tasks;
    for (const auto& [key, sessions] : sessions_of) tasks.insert(key.second);
    ExportFile out(out_dir / "README");
    out << "palprig trial export\n====================\n\n"
        << "Behavioural data of palpation studies run on a pneumatic multi-finger palpation rig with palprig, "
           "exported by `palprig export --format bids` from the trial store "
        << store.location() << ".\n\n"
        << participants.size() << " participants; tasks:";
    for (const std::string& t : tasks) out << " " << t;
    out << ".\n\nEach sub-<label>/beh/*_beh.tsv holds one session (a run), one row per trial; the JSON sidecar "
           "beside it describes every column, its levels and units. participants.tsv maps BIDS labels to the codes "
           "entered in palprig (sim:SEED is palprig's simulated participant).\n";
    commit_into(out, result.files);
  }
  {
    ExportFile out(out_dir / "participants.tsv");
    out << "participant_id\tcode\tsimulated\n";
    for (const auto& [code, simulated] : participants) {
      out << "sub-" << label_of[code] << "\t" << tsv_field(code) << "\t" << (simulated ? 1 : 0) << "\n";
    }
    commit_into(out, result.files);
    nlohmann::ordered_json pj;
    pj["participant_id"] = column("BIDS label: the palprig participant code reduced to letters and digits");
    pj["code"] = column("Participant code as entered in palprig (sim:SEED for a simulated participant)");
    pj["simulated"] = column("Whether the participant was palprig's simulated model observer", "",
                             {{"0", "a person"}, {"1", "simulated participant (model observer)"}});
    write_export_json(out_dir / "participants.json", pj, result.files);
  }

  for (const auto& [key, sessions] : sessions_of) {
    const auto& [label, task] = key;
    const auto dir = out_dir / ("sub-" + label) / "beh";
    make_export_dir(dir);
    for (std::size_t run = 0; run < sessions.size(); ++run) {
      std::string stem = "sub-" + label;
      stem.append("_task-").append(task);
      if (sessions.size() > 1) stem += "_run-" + std::to_string(run + 1);
      const std::int64_t session = sessions[run];
      std::vector<const ExportTrial*> rows;
      for (const ExportTrial& t : c.trials) {
        if (t.session == session) rows.push_back(&t);
      }
      std::vector<const ThresholdExportRow*> threshold_rows;
      for (const ThresholdExportRow& r : c.threshold) {
        if (r.session == session) threshold_rows.push_back(&r);
      }
      std::vector<const PulseExportRow*> pulse_rows;
      for (const PulseExportRow& r : c.pulse) {
        if (r.session == session) pulse_rows.push_back(&r);
      }
      if (!rows.empty())
        write_trials_run(rows, task, dir, stem, result.files);
      else if (!threshold_rows.empty())
        write_threshold_bids_run(threshold_rows, task, dir, stem, result.files);
      else
        write_pulse_bids_run(pulse_rows, task, dir, stem, result.files);
    }
  }
  return result;
}

}  // namespace palprig
