#include "store/trial_export.hpp"

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

#include "models/parse_error.hpp"

namespace palprig {

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
    throw InputError(file, where, "the protocol stored when the session started, as a JSON object (it no longer "
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

std::vector<ExportTrial> read_trials(TrialStore& store, const ExportOptions& options) {
  std::map<std::int64_t, std::array<std::string, kFingerCount>> finger_names;  // per session, from the protocol
  std::map<std::int64_t, nlohmann::json> confidence_scales;
  for (const SessionOverview& session : store.list_sessions()) {
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

std::string number(const std::optional<double>& x, int decimals = 4) {
  if (!x || !std::isfinite(*x)) return "n/a";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, *x);
  return buf;
}

std::string rating_text(const std::optional<int>& rating, const char* none) {
  return rating ? std::to_string(*rating) : std::string(none);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string tsv_field(const std::string& s) {
  std::string out;
  for (char c : s) out += (c == '\t' || c == '\n' || c == '\r') ? ' ' : c;
  return out.empty() ? "n/a" : out;
}

std::ofstream open_for_writing(const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path.string(), "file", "a writable output file");
  return out;
}

void make_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw InputError(dir.string(), "`out_dir`", "a folder that can be created");
}

std::string bit(const std::string& flags, int f) {
  if (flags.size() != kFingerCount) return "n/a";
  return std::string(1, flags[static_cast<std::size_t>(f)]);
}

// The BIDS sidecar entry of one column.
nlohmann::ordered_json column(const std::string& description, const std::string& units = "",
                              const nlohmann::ordered_json& levels = nullptr) {
  nlohmann::ordered_json c;
  c["Description"] = description;
  if (!levels.is_null()) c["Levels"] = levels;
  if (!units.empty()) c["Units"] = units;
  return c;
}

}  // namespace

std::string bids_label_of(const std::string& code) {
  std::string out;
  for (char c : code) {
    if (std::isalnum(static_cast<unsigned char>(c))) out += c;
  }
  return out.empty() ? "unnamed" : out;
}

ExportResult export_long_csv(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options) {
  make_dir(out_dir);
  const std::vector<ExportTrial> trials = read_trials(store, options);
  ExportResult result;
  result.trials = trials.size();

  const auto long_path = out_dir / "trials_long.csv";
  std::ofstream out = open_for_writing(long_path);
  out << "participant,simulated,session,protocol,task,trial,block,condition,mode,practice,combination,unit,finger,"
         "finger_name,tumor,stimulus_kPa,felt_kPa,tumor_present,answered,answered_tumor,outcome,response_time_s,"
         "onset_s,completed_utc,rt_after_stimulus_s,confidence\n";
  for (const ExportTrial& t : trials) {
    const std::string head = csv_field(t.participant) + "," + (t.simulated ? "1" : "0") + "," + std::to_string(t.session) +
                             "," + csv_field(t.protocol) + "," + t.task + "," + std::to_string(t.position + 1) + "," +
                             std::to_string(t.block + 1) + "," + csv_field(t.condition) + "," + t.mode + "," +
                             (t.practice ? "1" : "0") + "," + (t.combination_label.empty() ? "n/a" : t.combination_label);
    const std::string tail = std::string(t.answered ? "1" : "0");
    // rt_after_stimulus_s: from the stimulus end (n/a when unanswered or stored before the
    // column existed); confidence: empty when the protocol did not ask or no answer was given.
    const std::string times = number(t.response_time_s) + "," + number(t.onset_s) + "," + t.completed_utc + "," +
                              number(t.rt_after_stimulus_s) + "," + rating_text(t.confidence, "");
    if (t.mode != "scene") {
      for (int f = 0; f < kFingerCount; ++f) {
        const auto fi = static_cast<std::size_t>(f);
        out << head << ",finger" << f + 1 << "," << f + 1 << "," << csv_field(t.finger_names[fi]) << ",n/a,"
            << number(t.stimulus_kPa[fi], 3) << "," << number(t.felt_kPa[fi], 3) << "," << bit(t.truth, f) << "," << tail
            << "," << (t.answered ? bit(t.answer, f) : "n/a") << "," << (t.outcome[fi].empty() ? "n/a" : t.outcome[fi])
            << "," << times << "\n";
      }
    } else {
      for (const auto& [tumor, outcome] : t.tumor_outcomes) {
        out << head << ",tumor " << csv_field(tumor) << ",n/a,n/a," << csv_field(tumor) << ",n/a,n/a,1," << tail << ","
            << (outcome == "TP" ? "1" : "0") << "," << outcome << "," << times << "\n";
      }
      if (!t.answered || t.tumor_outcomes.empty()) {
        out << head << ",trial,n/a,n/a,n/a,n/a,n/a,n/a," << tail << ",n/a,n/a," << times << "\n";
      }
    }
  }
  result.files.push_back(long_path);

  const auto marks_path = out_dir / "marks.csv";
  std::ofstream marks = open_for_writing(marks_path);
  marks << "participant,session,trial,mark,x_mm,y_mm,tumor\n";
  for (const ExportTrial& t : trials) {  // ordered by participant, session, position; marks by mark
    for (const StoredMark& m : t.marks) {
      marks << csv_field(t.participant) << "," << t.session << "," << t.position + 1 << "," << m.mark + 1 << ","
            << number(m.x_mm, 2) << "," << number(m.y_mm, 2) << "," << (m.tumor ? csv_field(*m.tumor) : "n/a") << "\n";
    }
  }
  result.files.push_back(marks_path);
  return result;
}

ExportResult export_bids(TrialStore& store, const std::filesystem::path& out_dir, const ExportOptions& options) {
  make_dir(out_dir);
  const std::vector<ExportTrial> trials = read_trials(store, options);
  ExportResult result;
  result.trials = trials.size();

  // Participant labels, made unique when two codes reduce to the same letters and digits.
  std::map<std::string, std::string> label_of;
  std::set<std::string> used;
  std::vector<const ExportTrial*> first_of_participant;
  for (const ExportTrial& t : trials) {
    if (label_of.count(t.participant)) continue;
    std::string label = bids_label_of(t.participant);
    if (used.count(label)) label += "n" + std::to_string(t.participant_number);
    used.insert(label);
    label_of[t.participant] = label;
    first_of_participant.push_back(&t);
  }

  // Group trials into files: participant x task, one run per session.
  std::map<std::pair<std::string, std::string>, std::vector<std::int64_t>> sessions_of;  // (label, task) -> sessions
  for (const ExportTrial& t : trials) {
    auto& list = sessions_of[{label_of[t.participant], t.bids_task}];
    if (std::find(list.begin(), list.end(), t.session) == list.end()) list.push_back(t.session);
  }

  nlohmann::ordered_json description;
  description["Name"] = "palprig trial export";
  description["BIDSVersion"] = "1.8.0";
  description["DatasetType"] = "raw";
  description["GeneratedBy"] = {{{"Name", "palprig"}, {"Description", "palprig export --format bids"}}};
  {
    auto out = open_for_writing(out_dir / "dataset_description.json");
    out << description.dump(2) << "\n";
    result.files.push_back(out_dir / "dataset_description.json");
  }
  {
    auto out = open_for_writing(out_dir / "participants.tsv");
    out << "participant_id\tcode\tsimulated\n";
    for (const ExportTrial* t : first_of_participant) {
      out << "sub-" << label_of[t->participant] << "\t" << tsv_field(t->participant) << "\t" << (t->simulated ? 1 : 0) << "\n";
    }
    result.files.push_back(out_dir / "participants.tsv");
    nlohmann::ordered_json pj;
    pj["participant_id"] = column("BIDS label: the palprig participant code reduced to letters and digits");
    pj["code"] = column("Participant code as entered in palprig (sim:SEED for a simulated participant)");
    pj["simulated"] = column("Whether the participant was palprig's simulated model observer", "",
                             {{"0", "a person"}, {"1", "simulated participant (model observer)"}});
    auto js = open_for_writing(out_dir / "participants.json");
    js << pj.dump(2) << "\n";
    result.files.push_back(out_dir / "participants.json");
  }

  for (const auto& [key, sessions] : sessions_of) {
    const auto& [label, task] = key;
    const auto dir = out_dir / ("sub-" + label) / "beh";
    make_dir(dir);
    for (std::size_t run = 0; run < sessions.size(); ++run) {
      std::string stem = "sub-" + label + "_task-" + task;
      if (sessions.size() > 1) stem += "_run-" + std::to_string(run + 1);
      std::vector<const ExportTrial*> rows;
      for (const ExportTrial& t : trials) {
        if (t.session == sessions[run]) rows.push_back(&t);
      }
      const bool localisation = !rows.empty() && rows.front()->mode == "scene";
      std::vector<std::string> tumors;
      for (const ExportTrial* t : rows) {
        for (const auto& [tumor, outcome] : t->tumor_outcomes) {
          if (std::find(tumors.begin(), tumors.end(), tumor) == tumors.end()) tumors.push_back(tumor);
        }
      }

      auto tsv = open_for_writing(dir / (stem + "_beh.tsv"));
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
          side["stimulus_finger" + n] = column("Air pressure commanded under finger " + n + " (" + name + ")", "kPa");
          side["felt_finger" + n] = column("Mean regulator monitor pressure under finger " + n +
                                               " while its stimulus was on", "kPa");
          side["tumor_finger" + n] = column("Ground truth: tumor under finger " + n + " by paper 002's rule", "",
                                            {{"0", "no tumor"}, {"1", "tumor"}});
          side["response_finger" + n] = column("Participant answered a tumor under finger " + n, "",
                                               {{"0", "no"}, {"1", "yes"}});
          side["outcome_finger" + n] = column("Score of finger " + n + "'s value", "",
                                              {{"TP", "true positive"}, {"FN", "false negative"},
                                               {"TN", "true negative"}, {"FP", "false positive"}});
        }
      } else {
        for (const auto& tumor : tumors) {
          tsv << "\tdetected_" << tumor;
          side["detected_" + tumor] = column("Tumor " + tumor + " detected: a mark within its outline plus the tolerance",
                                             "", {{"TP", "detected"}, {"FN", "missed"}});
        }
        tsv << "\tfalse_marks";
        side["false_marks"] = column("Marks near no tumor");
      }
      tsv << "\tresponse_time\tonset\trt_after_stimulus";
      side["response_time"] = column("Time from stimulus onset to the answer (n/a when the response timed out); "
                                     "paper 002's measure, which includes a sequential presentation", "s");
      side["onset"] = column("Stimulus onset on the session's monotonic clock", "s");
      side["rt_after_stimulus"] = column("Time from the end of the stimulus to the answer (0 when answered during the "
                                         "stimulus; n/a when the response timed out or was not recorded)", "s");
      const nlohmann::json& scale = rows.empty() ? nlohmann::json() : rows.front()->confidence_scale;
      if (!scale.is_null()) {
        tsv << "\tconfidence";
        nlohmann::ordered_json levels;
        const int count = scale.value("levels", 0);
        const auto labels = scale.find("labels");
        for (int level = 1; level <= count; ++level) {
          const bool labelled = labels != scale.end() && labels->is_array() && labels->size() == static_cast<std::size_t>(count);
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
            tsv << "\t" << number(t->stimulus_kPa[fi], 3) << "\t" << number(t->felt_kPa[fi], 3) << "\t"
                << bit(t->truth, f) << "\t" << (t->answered ? bit(t->answer, f) : "n/a") << "\t"
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
          tsv << "\t" << (t->false_marks ? std::to_string(*t->false_marks) : "n/a");
        }
        tsv << "\t" << number(t->response_time_s) << "\t" << number(t->onset_s) << "\t" << number(t->rt_after_stimulus_s);
        if (!scale.is_null()) tsv << "\t" << rating_text(t->confidence, "n/a");
        tsv << "\n";
      }
      result.files.push_back(dir / (stem + "_beh.tsv"));
      auto js = open_for_writing(dir / (stem + "_beh.json"));
      js << side.dump(2) << "\n";
      result.files.push_back(dir / (stem + "_beh.json"));
    }
  }
  return result;
}

}  // namespace palprig
