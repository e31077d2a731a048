#include "store/trials_csv.hpp"

#include <string>

#include "store/export_file.hpp"
#include "store/export_text.hpp"

namespace palprig {

using namespace export_text;  // number, csv_field

namespace {

std::string flag(bool b) { return b ? "1" : "0"; }

// "010" -> "2": the fingers set in a stored truth or answer, 1-based ("none" when none is).
std::string fingers_of(const std::string& flags) {
  if (flags.size() != kFingerCount) return "n/a";
  std::string out;
  for (std::size_t f = 0; f < kFingerCount; ++f)
    if (flags[f] == '1') out += std::to_string(f + 1);
  return out.empty() ? "none" : out;
}

}  // namespace

void write_trials_csv(const std::vector<const StoredTrial*>& trials, const std::filesystem::path& file,
                      std::vector<std::filesystem::path>& written) {
  ExportFile out(file);
  out << "participant,simulated,session,protocol,task,trial,block,condition,mode,practice,combination";
  for (int f = 1; f <= kFingerCount; ++f) out << ",stimulus_finger" << f << "_kPa";
  for (int f = 1; f <= kFingerCount; ++f) out << ",felt_finger" << f << "_kPa";
  out << ",tumor_fingers,answered,answered_fingers";
  for (int f = 1; f <= kFingerCount; ++f) out << ",outcome_finger" << f;
  out << ",correct,tumors,tumors_found,false_marks,response_time_s,onset_s,completed_utc,rt_after_stimulus_s,"
         "confidence,stimulus_reached_s,rt_from_reached_s\n";
  for (const StoredTrial* p : trials) {
    const StoredTrial& t = *p;
    const bool scene = t.mode == "scene";
    out << csv_field(t.participant) << "," << flag(t.simulated) << "," << t.session << "," << csv_field(t.protocol)
        << "," << t.task << "," << t.position + 1 << "," << t.block + 1 << "," << csv_field(t.condition) << ","
        << t.mode << "," << flag(t.practice) << "," << (t.combination_label.empty() ? "n/a" : t.combination_label);
    for (const auto& v : t.stimulus_kPa) out << "," << number(v, 3);
    for (const auto& v : t.felt_kPa) out << "," << number(v, 3);
    out << "," << (scene ? "n/a" : fingers_of(t.truth)) << "," << flag(t.answered) << ","
        << (scene || !t.answered ? "n/a" : fingers_of(t.answer));
    bool all_right = t.answered;
    for (const std::string& o : t.outcome) {
      out << "," << (o.empty() ? "n/a" : o);
      all_right = all_right && (o == "TP" || o == "TN");
    }
    // correct: every finger value right (discrimination); every tumor found and no false mark
    // (localisation).
    int found = 0;
    for (const auto& [tumor, outcome] : t.tumor_outcomes) found += outcome == "TP" ? 1 : 0;
    if (scene) {
      const bool clean =
          t.answered && found == static_cast<int>(t.tumor_outcomes.size()) && t.false_marks.value_or(0) == 0;
      out << "," << flag(clean) << "," << t.tumor_outcomes.size() << "," << (t.answered ? std::to_string(found) : "n/a")
          << "," << (t.false_marks ? std::to_string(*t.false_marks) : std::string("n/a"));
    } else {
      out << "," << (t.answered ? flag(all_right) : "n/a") << ",n/a,n/a,n/a";
    }
    out << "," << number(t.response_time_s) << "," << number(t.onset_s) << "," << t.completed_utc << ","
        << number(t.rt_after_stimulus_s) << "," << (t.confidence ? std::to_string(*t.confidence) : std::string()) << ","
        << number(t.stimulus_reached_s) << "," << number(t.rt_from_reached_s) << "\n";
  }
  commit_into(out, written);
}

}  // namespace palprig
