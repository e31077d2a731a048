#include "sessions/training_session.hpp"

// A trainee's next session and their standing (sessions/training_session.hpp). The one place
// the training programme calls the session API: run_study_session for tumor levels,
// run_pulse_study for pulse levels (both below, in run_level_session).
#include <algorithm>
#include <map>

#include "core/input_error.hpp"
#include "store/pg_target.hpp"
#include "store/postgres_trial_store.hpp"
#include "store/sqlite_trial_store.hpp"
#include "study/localisation_case.hpp"
#include "study/pulse_protocol.hpp"

namespace palprig {

namespace {

// Forwards a study session's events to the front end, notes the new session as the trainee's
// before its first trial, and keeps each committed case.
class TrainingStudyListener final : public SessionListener {
 public:
  TrainingStudyListener(SessionListener* forward, std::function<void(const SessionStart&)> started)
      : forward_(forward), started_(std::move(started)) {}
  void session_started(const SessionStart& s) override {
    started_(s);
    start_ = s;
    if (forward_) forward_->session_started(s);
  }
  void runner_event(const RunnerEvent& e) override {
    if (forward_) forward_->runner_event(e);
  }
  void trial_started(const PlannedTrial& t, const Condition& c) override {
    if (forward_) forward_->trial_started(t, c);
  }
  void trial_committed(const TrialRecord& t, int total) override {
    cases.push_back(case_result(t));
    if (forward_) forward_->trial_committed(t, total);
  }
  void participant_feedback(int position, const std::string& text) override {
    if (forward_) forward_->participant_feedback(position, text);
  }
  void session_ended(const SessionEnd& e) override {
    if (forward_) forward_->session_ended(e);
  }
  std::vector<CaseResult> cases;
  SessionStart start_;

 private:
  SessionListener* forward_;
  std::function<void(const SessionStart&)> started_;
};

class TrainingPulseListener final : public PulseSessionListener {
 public:
  TrainingPulseListener(PulseSessionListener* forward, std::function<void(const SessionStart&)> started)
      : forward_(forward), started_(std::move(started)) {}
  void session_started(const SessionStart& s) override {
    started_(s);
    start_ = s;
    if (forward_) forward_->session_started(s);
  }
  void trial_started(const PulseTrialStart& s, const PulseCondition& c) override {
    if (forward_) forward_->trial_started(s, c);
  }
  void waiting(int position, bool paused) override {
    if (forward_) forward_->waiting(position, paused);
  }
  void trial_committed(const PulseTrialRecord& t, int total) override {
    cases.push_back(case_result(t));
    if (forward_) forward_->trial_committed(t, total);
  }
  void session_ended(const SessionEnd& e) override {
    if (forward_) forward_->session_ended(e);
  }
  std::vector<CaseResult> cases;
  SessionStart start_;

 private:
  PulseSessionListener* forward_;
  std::function<void(const SessionStart&)> started_;
};

// The case keys a stored training protocol gives (a session whose training row was never
// written: its process ended between creating the session and writing the row).
std::vector<std::string> case_keys_of(const nlohmann::json& protocol, const std::filesystem::path& base,
                                      const std::string& source) {
  std::vector<std::string> keys;
  if (protocol.value("task", std::string()) == "pulse") {
    for (const PulseCondition& c : parse_pulse_protocol(protocol, source, base).conditions) {
      if (c.generated && c.generated_seed)
        keys.push_back(std::string("pulse:") + to_string(*c.generated) + ":" + std::to_string(*c.generated_seed));
    }
    return keys;
  }
  for (const LocalisationCase& c : parse_protocol(protocol, source, base).localisation.cases)
    keys.push_back(case_key(c));
  return keys;
}

}  // namespace

PreparedTraining prepare_training_session(const TrainingRequest& r) {
  PreparedTraining p;
  p.curriculum = load_curriculum(r.curriculum_file);
  const Curriculum& curriculum = p.curriculum;
  std::optional<std::uint64_t>& sim_seed = p.simulated_seed;
  if (r.simulated_skill && (r.participant.empty() || !(*r.simulated_skill >= 0 && *r.simulated_skill <= 1))) {
    throw InputError("command line", "sim_skill", "a skill 0..1 for a simulated trainee (with participant sim:SEED)");
  }
  if (!r.participant.empty()) {
    std::uint64_t seed = 0;
    if (!parse_simulated_participant(r.participant, seed)) {
      throw InputError(
          "command line", "participant",
          "sim:SEED (a simulated trainee for a pilot), or none for the trainee themself; got '" + r.participant + "'");
    }
    sim_seed = seed;
  }
  const auto store = open_training_store(r.store_location, TrialStore::Access::read_write);
  require_enrolled(*store, curriculum, r.trainee);
  std::vector<TrainingSessionRecord> history = store->training_sessions(r.trainee);
  complete_left_behind(*store, curriculum, history);

  const std::vector<TrainingSessionRecord> mine = of_curriculum(history, curriculum.name);
  const TrainingStanding before = training_standing(curriculum, mine);
  TrainingPlanView& plan_view = p.plan;
  plan_view.trainee = r.trainee;
  plan_view.curriculum = curriculum.name;

  std::map<std::int64_t, std::string> status;
  for (const SessionOverview& s : store->list_sessions()) status[s.id] = s.status;
  // The trainee's unfinished session is continued before any new one.
  std::optional<TrainingSessionRecord>& unfinished = p.unfinished;
  for (const auto& h : mine) {
    if (!h.completed() && status[h.session_id] == "running") unfinished = h;
  }
  int& cases_practised = p.cases_practised;
  std::set<std::string> given;
  for (const auto& h : history) {
    given.insert(h.cases.begin(), h.cases.end());
    if (h.completed() && (!unfinished || h.session_id != unfinished->session_id))
      cases_practised += static_cast<int>(h.cases.size());
  }

  p.curriculum_file = std::filesystem::absolute(r.curriculum_file);
  const std::filesystem::path& curriculum_file = p.curriculum_file;
  if (!unfinished) {
    // A session of the trainee's level started without its training row (the process ended
    // between the two): adopted and continued.
    const int level = r.level ? level_index(curriculum, *r.level)
                              : std::min<int>(before.level, static_cast<int>(curriculum.levels.size()) - 1);
    if (const auto who = store->find_participant(r.trainee)) {
      if (const auto id = store->find_unfinished_session(*who, training_protocol_name(curriculum, level))) {
        TrainingSessionRecord adopted;
        adopted.session_id = *id;
        adopted.trainee = r.trainee;
        adopted.curriculum = curriculum.name;
        adopted.level = level;
        adopted.level_name = curriculum.levels.at(static_cast<std::size_t>(level)).name;
        adopted.cases = case_keys_of(store->protocol_snapshot(*id), curriculum_file.parent_path(), curriculum.source);
        store->begin_training_session(adopted);
        unfinished = adopted;
      }
    }
  }

  nlohmann::json& protocol = p.protocol;
  std::vector<std::string>& keys = p.keys;
  if (unfinished) {
    const CurriculumLevel* level = level_named(curriculum, unfinished->level_name);
    plan_view.level = level ? static_cast<int>(level - curriculum.levels.data()) : unfinished->level;
    plan_view.level_name = unfinished->level_name;
    plan_view.resumed = true;
    protocol = store->protocol_snapshot(unfinished->session_id);
    keys = unfinished->cases;
    plan_view.session_number = static_cast<int>(mine.size());
  } else {
    if (!r.level && before.finished) {
      throw InputError(store->location(), "trainee '" + r.trainee + "'",
                       "a trainee with a level left in '" + curriculum.name + "' (they passed every level after " +
                           std::to_string(before.sessions) + " sessions; --level NAME runs a level again)");
    }
    plan_view.level = r.level ? level_index(curriculum, *r.level) : before.level;
    plan_view.level_name = curriculum.levels.at(static_cast<std::size_t>(plan_view.level)).name;
    plan_view.session_number = static_cast<int>(mine.size()) + 1;
    const PlannedTrainingSession plan =
        plan_training_session(curriculum, plan_view.level, r.trainee, given, plan_view.session_number);
    protocol = plan.protocol;
    for (const auto& c : plan.cases) keys.push_back(c.key);
  }
  const CurriculumLevel& level = curriculum.levels.at(static_cast<std::size_t>(plan_view.level));
  plan_view.pulse = level.cases == LevelCases::generated_pulse;
  if (plan_view.pulse && is_server_store_location(r.store_location)) {
    throw InputError(r.store_location, "`store`",
                     "an SQLite file for curriculum '" + curriculum.name + "': level '" + level.name +
                         "' has pulse cases, whose trials are not stored on the PostgreSQL lab server");
  }
  if (!unfinished) keys = case_keys_of(protocol, curriculum_file.parent_path(), curriculum.source);
  if (plan_view.pulse) {
    for (const auto& c : protocol.at("conditions")) plan_view.cases.push_back(c.value("name", std::string()));
  } else {
    for (const auto& c : parse_protocol(protocol, curriculum.source, curriculum_file.parent_path()).localisation.cases)
      plan_view.cases.push_back(c.name);
  }
  return p;
}

TrainingOutcome run_training_session(const TrainingRequest& r, const TrainingFrontEnd& front,
                                     const RunControl& control) {
  return run_training_session(r, prepare_training_session(r), front, control);
}

TrainingOutcome run_training_session(const TrainingRequest& r, const PreparedTraining& p, const TrainingFrontEnd& front,
                                     const RunControl& control) {
  const Curriculum& curriculum = p.curriculum;
  const std::filesystem::path& curriculum_file = p.curriculum_file;
  const std::optional<TrainingSessionRecord>& unfinished = p.unfinished;
  const std::vector<std::string>& keys = p.keys;
  const nlohmann::json& protocol = p.protocol;
  const std::optional<std::uint64_t>& sim_seed = p.simulated_seed;
  const int cases_practised = p.cases_practised;
  const auto store = open_training_store(r.store_location, TrialStore::Access::read_write);
  TrainingOutcome out;
  out.plan = p.plan;
  out.before = training_standing(curriculum, of_curriculum(store->training_sessions(r.trainee), curriculum.name));
  const CurriculumLevel& level = curriculum.levels.at(static_cast<std::size_t>(out.plan.level));
  if (front.planned) front.planned(out.plan);

  StudySessionRequest request;
  request.protocol_file = curriculum_file;
  request.protocol_document = protocol;
  request.participant_code = r.trainee;
  request.store_location = r.store_location;
  request.journal_file = r.journal_file;
  request.rig_file = r.rig_file;
  request.calibration_file = r.calibration_file;
  request.telemetry_file = r.telemetry_file;
  request.resume = unfinished.has_value();
  request.speed = r.speed;
  request.simulated_seed = sim_seed;
  request.model.skill = r.simulated_skill ? ObserverSkill{CurriculumPilot{*r.simulated_skill, 0.0}, 0}
                                          : ObserverSkill{curriculum.pilot, cases_practised};
  request.person_palpates = r.person_palpates;
  request.tick_observer = r.tick_observer;
  request.rig = r.rig;

  // Noted as the trainee's before its first trial: its cases are theirs from now on.
  const auto begin = [&](const SessionStart& s) {
    if (s.resumed && unfinished) return;
    TrainingSessionRecord record;
    record.session_id = s.session_id;
    record.trainee = r.trainee;
    record.curriculum = curriculum.name;
    record.level = out.plan.level;
    record.level_name = level.name;
    record.cases = keys;
    store->begin_training_session(record);
  };
  std::vector<CaseResult> cases;
  SessionStart start;
  if (out.plan.pulse) {
    TrainingPulseListener listener(front.pulse_listener, begin);
    out.end = run_pulse_study(request, front.pulse_person, listener, control);
    cases = listener.cases;
    start = listener.start_;
  } else {
    TrainingStudyListener listener(front.listener, begin);
    out.end = run_study_session(request, front.person, listener, control);
    cases = listener.cases;
    start = listener.start_;
  }
  if (out.end.completed) {
    out.scores.cases = start.start_position > 0
                           ? stored_cases(*store, start.session_id, out.plan.pulse, start.start_position)
                           : std::vector<CaseResult>{};
    out.scores.cases.insert(out.scores.cases.end(), cases.begin(), cases.end());
    out.benchmark = check_benchmark(level.benchmark, out.scores);
    store->complete_training_session(start.session_id, to_json(out.scores), out.benchmark.met);
    out.scored = true;
  }
  out.after = training_standing(curriculum, of_curriculum(store->training_sessions(r.trainee), curriculum.name));
  return out;
}

}  // namespace palprig
