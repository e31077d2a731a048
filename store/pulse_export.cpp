#include "store/pulse_export.hpp"

#include <cmath>

#include "core/input_error.hpp"
#include "store/export_file.hpp"
#include "store/export_text.hpp"
#include "store/pulse_store.hpp"

namespace palprig {

using namespace export_text;  // number, csv_field, tsv_field, column

namespace {

// The hit radius the session scored with, from its stored protocol (the protocol's default when
// absent). Read from the snapshot's JSON, not through the protocol parser, which loads every
// scene file the protocol names: an analyst's machine need not hold them.
double stored_hit_radius_mm(SqliteTrialStore& store, std::int64_t session) {
  const nlohmann::json snapshot = store.protocol_snapshot(session);
  const auto pulse = snapshot.find("pulse");
  if (pulse == snapshot.end() || !pulse->is_object() || !pulse->contains("hit_radius_mm")) return 5.0;
  const auto& r = (*pulse)["hit_radius_mm"];
  if (!r.is_number() || !(r.get<double>() > 0)) {
    throw InputError(store.location(),
                     "sessions.protocol_json of session " + std::to_string(session) + ": pulse.hit_radius_mm",
                     "the positive hit radius stored when the session started");
  }
  return r.get<double>();
}

std::string seed_text(const PulseTrialRecord& t) { return t.scene_seed ? std::to_string(*t.scene_seed) : "n/a"; }

}  // namespace

std::vector<PulseExportRow> pulse_export_rows(SqliteTrialStore& store, const std::vector<SessionOverview>& sessions) {
  std::vector<PulseExportRow> out;
  PulseStore pulse(store, false);
  for (const SessionOverview& session : sessions) {
    if (session.task != "pulse") continue;
    const std::vector<PulseTrialRecord> trials = pulse.read_trials(session.id);
    if (trials.empty()) continue;
    const double radius = stored_hit_radius_mm(store, session.id);
    for (const PulseTrialRecord& t : trials) {
      PulseExportRow row;
      row.session = session.id;
      row.participant = session.participant;
      row.protocol = session.protocol_name;
      row.hit_radius_mm = radius;
      row.trial = t;
      out.push_back(std::move(row));
    }
  }
  return out;
}

void write_pulse_csv(const std::vector<PulseExportRow>& rows, const std::filesystem::path& file) {
  ExportFile out(file);
  out << "participant,simulated,session,protocol,task,trial,condition,scene_seed,artery,answered,mark_x_mm,mark_y_mm,"
         "distance_mm,hit,hit_radius_mm,response_time_s,onset_s\n";
  std::size_t n = 0;
  for (const PulseExportRow& r : rows) {
    const PulseTrialRecord& t = r.trial;
    out << csv_field(r.participant.code) << "," << (r.participant.simulated ? 1 : 0) << "," << r.session << ","
        << csv_field(r.protocol) << ",pulse," << t.position + 1 << "," << csv_field(t.condition) << "," << seed_text(t)
        << "," << (t.artery.empty() ? "n/a" : csv_field(t.artery)) << "," << (t.answered ? 1 : 0) << ","
        << (t.answered ? number(t.mark_x_mm, 2) : "n/a") << "," << (t.answered ? number(t.mark_y_mm, 2) : "n/a") << ","
        << (t.answered ? number(t.distance_mm, 2) : "n/a") << "," << (t.answered ? (t.hit ? "1" : "0") : "n/a") << ","
        << number(r.hit_radius_mm, 2) << "," << (t.answered ? number(t.response_time_s) : "n/a") << ","
        << number(t.onset_s) << "\n";
    if (++n % 4096 == 0) out.check();
  }
  out.commit();
}

void write_pulse_bids_run(const std::vector<const PulseExportRow*>& rows, const std::string& task,
                          const std::filesystem::path& dir, const std::string& stem,
                          std::vector<std::filesystem::path>& written) {
  const PulseExportRow& first = *rows.front();
  ExportFile tsv(dir / (stem + "_beh.tsv"));
  tsv << "trial\tcondition\tscene_seed\tartery\tmark_x\tmark_y\tdistance_to_artery\thit\tresponse_time\tonset\n";
  for (const PulseExportRow* r : rows) {
    const PulseTrialRecord& t = r->trial;
    tsv << t.position + 1 << "\t" << tsv_field(t.condition) << "\t" << seed_text(t) << "\t" << tsv_field(t.artery)
        << "\t" << (t.answered ? number(t.mark_x_mm, 2) : "n/a") << "\t"
        << (t.answered ? number(t.mark_y_mm, 2) : "n/a") << "\t" << (t.answered ? number(t.distance_mm, 2) : "n/a")
        << "\t" << (t.answered ? (t.hit ? "1" : "0") : "n/a") << "\t"
        << (t.answered ? number(t.response_time_s) : "n/a") << "\t" << number(t.onset_s) << "\n";
  }
  commit_into(tsv, written);

  nlohmann::ordered_json side;
  side["TaskName"] = task;
  side["TaskDescription"] = "palprig protocol " + first.protocol +
                            ": the participant palpates a scene with one or more pulsing arteries and marks where "
                            "the pulse is; a mark within " +
                            number(first.hit_radius_mm, 1) + " mm of the artery's centreline is a hit";
  side["trial"] = column("Position of the trial in the session (1-based)");
  side["condition"] = column("Condition name from the protocol (the scene palpated)");
  side["scene_seed"] = column("Seed of the generated case the trial presented (n/a: a fixed scene)");
  side["artery"] = column("The artery the mark was scored against");
  side["mark_x"] = column("Marked position, x on the scene (n/a: no mark before the time limit)", "mm");
  side["mark_y"] = column("Marked position, y on the scene (n/a: no mark)", "mm");
  side["distance_to_artery"] = column("Distance from the mark to the artery's centreline (n/a: no mark)", "mm");
  side["hit"] = column("The mark lies within the hit radius of the centreline", "", {{"0", "miss"}, {"1", "hit"}});
  side["response_time"] = column("Time from the scene's presentation to the mark (n/a: no mark)", "s");
  side["onset"] = column("Presentation onset on the session's monotonic clock", "s");
  write_export_json(dir / (stem + "_beh.json"), side, written);
}

}  // namespace palprig
