#include "store/threshold_export.hpp"

#include <map>
#include <stdexcept>

#include "core/input_error.hpp"
#include "store/export_file.hpp"
#include "store/export_text.hpp"
#include "store/threshold_store.hpp"
#include "study/threshold_protocol.hpp"

namespace palprig {

using namespace export_text;  // number, csv_field, tsv_field, column

namespace {

// The answer as words: which interval (2AFC, 1-based) or yes/no; n/a without an answer.
std::string response_text(const ThresholdExportRow& r) {
  if (!r.trial.answered) return "n/a";
  if (r.method == "yes-no") return r.trial.response == 1 ? "yes" : "no";
  return "interval" + std::to_string(r.trial.response + 1);
}

}  // namespace

std::vector<ThresholdExportRow> threshold_export_rows(SqliteTrialStore& store,
                                                      const std::vector<SessionOverview>& sessions) {
  std::vector<ThresholdExportRow> out;
  ThresholdStore threshold(store, false);
  if (!threshold.has_table()) return out;
  std::map<std::int64_t, std::vector<ThresholdTrialRecord>> by_session;
  for (ThresholdTrialRow& row : threshold.trials()) by_session[row.session_id].push_back(std::move(row.trial));
  for (const SessionOverview& session : sessions) {
    const auto it = by_session.find(session.id);
    if (session.task != "threshold" || it == by_session.end()) continue;
    const std::string where = "session " + std::to_string(session.id);
    ThresholdProtocol protocol;
    try {
      protocol = parse_threshold_protocol(store.protocol_snapshot(session.id), store.location());
    } catch (const InputError& e) {
      throw InputError(store.location(), "sessions.protocol_json of " + where,
                       std::string("the threshold protocol stored when the session started (") + e.what() + ")");
    }
    std::vector<AdaptiveTrack> tracks;
    for (const TrackSpec& spec : protocol.tracks) tracks.emplace_back(spec);
    try {
      replay_tracks(tracks, it->second, [&](const ThresholdTrialRecord& r, const std::vector<AdaptiveTrack>& after) {
        ThresholdExportRow row;
        row.session = session.id;
        row.participant = session.participant;
        row.protocol = session.protocol_name;
        row.method = to_string(protocol.method);
        const AdaptiveTrack& track = after[static_cast<std::size_t>(r.track)];
        row.procedure = track.spec().procedure == AdaptiveProcedure::quest ? "quest" : "staircase";
        row.trial = r;
        row.estimate = track.estimate();
        row.estimate_kPa = row.estimate.threshold_kPa;
        row.track_finished = track.finished();
        out.push_back(std::move(row));
      });
    } catch (const BadInput& e) {  // the study's replay refused a stored trial
      throw InputError(store.location(), "threshold_trials of " + where,
                       std::string("trials the stored protocol's tracks can replay (") + e.what() + ")");
    }
  }
  return out;
}

void write_threshold_csv(const std::vector<ThresholdExportRow>& rows, const std::filesystem::path& file) {
  ExportFile out(file);
  out << "participant,simulated,session,protocol,task,method,trial,track,track_name,fingers,procedure,reference_kPa,"
         "level_kPa,signal_interval,answered,response,correct,reversal,estimate_kPa,response_time_s,onset_s,"
         "felt_interval1_kPa,felt_interval2_kPa\n";
  std::size_t n = 0;
  for (const ThresholdExportRow& r : rows) {
    const ThresholdTrialRecord& t = r.trial;
    out << csv_field(r.participant.code) << "," << (r.participant.simulated ? 1 : 0) << "," << r.session << ","
        << csv_field(r.protocol) << ",threshold," << r.method << "," << t.position + 1 << "," << t.track + 1 << ","
        << csv_field(t.track_name) << "," << t.fingers << "," << r.procedure << "," << number(t.reference_kPa, 4) << ","
        << number(t.level_kPa, 4) << "," << t.signal_interval + 1 << "," << (t.answered ? 1 : 0) << ","
        << response_text(r) << "," << (t.answered ? (t.correct ? "1" : "0") : "n/a") << "," << (t.reversal ? 1 : 0)
        << "," << number(r.estimate_kPa, 4) << "," << number(t.answered ? t.response_time_s : NAN) << ","
        << number(t.onset_s) << "," << number(t.felt_kPa[0], 3) << "," << number(t.felt_kPa[1], 3) << "\n";
    if (++n % 4096 == 0) out.check();
  }
  out.commit();
}

void write_threshold_bids_run(const std::vector<const ThresholdExportRow*>& rows, const std::string& task,
                              const std::filesystem::path& dir, const std::string& stem,
                              std::vector<std::filesystem::path>& written) {
  const ThresholdExportRow& first = *rows.front();
  const bool two_afc = first.method != "yes-no";
  ExportFile tsv(dir / (stem + "_beh.tsv"));
  tsv << "trial\ttrack\ttrack_name\tfingers\tprocedure\treference_pressure\tlevel\tsignal_interval\tresponse\tcorrect\t"
         "reversal\tthreshold_estimate\tresponse_time\tonset\tfelt_interval1\tfelt_interval2\n";
  for (const ThresholdExportRow* r : rows) {
    const ThresholdTrialRecord& t = r->trial;
    tsv << t.position + 1 << "\t" << t.track + 1 << "\t" << tsv_field(t.track_name) << "\t" << t.fingers << "\t"
        << r->procedure << "\t" << number(t.reference_kPa, 4) << "\t" << number(t.level_kPa, 4) << "\t"
        << t.signal_interval + 1 << "\t" << response_text(*r) << "\t" << (t.answered ? (t.correct ? "1" : "0") : "n/a")
        << "\t" << (t.reversal ? 1 : 0) << "\t" << number(r->estimate_kPa, 4) << "\t"
        << number(t.answered ? t.response_time_s : NAN) << "\t" << number(t.onset_s) << "\t" << number(t.felt_kPa[0], 3)
        << "\t" << number(t.felt_kPa[1], 3) << "\n";
  }
  commit_into(tsv, written);

  nlohmann::ordered_json side;
  side["TaskName"] = task;
  side["TaskDescription"] =
      "palprig protocol " + first.protocol + ": adaptive measurement of the pressure increment detected over a " +
      "reference pressure, " +
      (two_afc ? "two-interval forced choice (which interval was stronger)" : "yes/no (did the second feel stronger)") +
      "; tracks interleaved at random";
  side["trial"] = column("Position of the trial in the session (1-based)");
  side["track"] = column("Adaptive track of the trial (1-based, in the protocol's order)");
  side["track_name"] = column("Name of the track in the protocol");
  side["fingers"] = column("Fingers stimulated", "", {{"one", "one finger"}, {"three", "all three fingers"}});
  side["procedure"] = column(
      "Adaptive procedure of the track", "",
      {{"staircase", "transformed up-down staircase (Levitt 1971)"}, {"quest", "QUEST (Watson and Pelli 1983)"}});
  side["reference_pressure"] = column("Reference air pressure under the stimulated fingers", "kPa");
  side["level"] = column("Pressure increment over the reference presented in the signal interval", "kPa");
  side["signal_interval"] = column(two_afc ? "Interval that held reference + level"
                                           : "Interval that held reference + level "
                                             "(always the second in yes/no)",
                                   "", {{"1", "first interval"}, {"2", "second interval"}});
  side["response"] = two_afc
                         ? column("Interval the participant chose as stronger (n/a: no answer, the trial was repeated)",
                                  "", {{"interval1", "first"}, {"interval2", "second"}})
                         : column("Whether the second interval felt stronger (n/a: no answer, the trial was repeated)",
                                  "", {{"yes", "stronger"}, {"no", "not stronger"}});
  side["correct"] = column(two_afc ? "Chose the signal interval" : "Answered yes (counted as correct by the track)", "",
                           {{"0", "no"}, {"1", "yes"}});
  side["reversal"] = column("The answer reversed the track's direction (staircases; 0 for QUEST)", "",
                            {{"0", "no"}, {"1", "reversal"}});
  side["threshold_estimate"] = column(
      "The track's threshold estimate after this trial: the mean of its last reversals "
      "(staircase; the current level before any) or the posterior mean (QUEST)",
      "kPa");
  side["response_time"] = column("Time from the end of the second interval to the answer", "s");
  side["onset"] = column("Trial onset on the session's monotonic clock", "s");
  side["felt_interval1"] = column(
      "Mean regulator monitor pressure on the stimulated fingers in the first interval's "
      "second half",
      "kPa");
  side["felt_interval2"] = column("Same for the second interval", "kPa");
  write_export_json(dir / (stem + "_beh.json"), side, written);
}

}  // namespace palprig
