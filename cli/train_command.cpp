// palprig train enrol|next|status|benchmark: a training programme over a curriculum file
// (study/curriculum.hpp) and a trial store: trainees enrolled, their next session at their level,
// where each stands, and a level's benchmark from experts' sessions. The library calls are
// sessions/training_session.hpp (next) and store/training_history.hpp (the rest).
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "formats/json_file.hpp"
#include "io/checked_output.hpp"
#include "sessions/session_telemetry.hpp"
#include "sessions/training_session.hpp"

namespace {

using namespace palprig;

std::string fixed(std::optional<double> x, int decimals) {
  if (!x || !std::isfinite(*x)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, *x);
  return buf;
}

// "level 2 of 3 'medium tumors'", or "every level passed".
std::string level_text(const Curriculum& c, int level) {
  if (level >= static_cast<int>(c.levels.size())) return "every level passed";
  return "level " + std::to_string(level + 1) + " of " + std::to_string(c.levels.size()) + " '" +
         c.levels[static_cast<std::size_t>(level)].name + "'";
}

std::string scores_line(const SessionScores& s) {
  std::string line = "tumors found " + fixed(s.found_fraction(), 2) + " (" + std::to_string(s.found()) + " of " +
                     std::to_string(s.targets()) + "), false marks per case " + fixed(s.false_marks_per_case(), 2) +
                     ", " + fixed(s.time_per_case_s(), 1) + " s per case";
  if (s.normal_cases() > 0) {
    line +=
        ", normal cases called normal " + std::to_string(s.normal_called()) + " of " + std::to_string(s.normal_cases());
  }
  return line;
}

std::string case_line(const CaseResult& c, int index, int total) {
  std::string line = "  case " + std::to_string(index) + "/" + std::to_string(total) + " " + c.name + ": ";
  if (!c.answered) return line + "no answer";
  if (c.pulse) {
    line += c.found ? "pulse found" : "pulse missed";
  } else if (c.normal()) {
    line += c.false_marks == 0 ? "no tumor, none marked (TN)" : "no tumor, marked (FP)";
  } else {
    line += std::to_string(c.found) + " of " + std::to_string(c.tumors) + " tumors found";
    if (c.false_marks > 0) line += ", " + cli::counted(c.false_marks, "false mark", "false marks");
  }
  return line + ", " + fixed(c.time_s, 1) + " s";
}

// Prints each committed case of a simulated trainee (a person sees the prompts instead).
class TrainReport final : public SessionListener {
 public:
  explicit TrainReport(bool quiet) : quiet_(quiet) {}
  void session_started(const SessionStart& s) override {
    total_ = s.total_trials;
    simulated_ = s.simulated;
    session_ = s.session_id;
  }
  void trial_committed(const TrialRecord& t, int total) override {
    if (simulated_ && !quiet_)
      std::cout << case_line(case_result(t), t.planned.position + 1, total) << "\n" << std::flush;
  }
  void trial_committed(const PulseTrialRecord& t, int total) {
    if (simulated_ && !quiet_) std::cout << case_line(case_result(t), t.position + 1, total) << "\n" << std::flush;
  }
  void participant_feedback(int, const std::string& text) override {
    if (!simulated_) std::cout << "  " << text << "\n" << std::flush;
  }
  std::int64_t session() const noexcept { return session_; }

 private:
  bool quiet_;
  bool simulated_ = false;
  int total_ = 0;
  std::int64_t session_ = 0;
};

// The pulse listener's session_started has the same signature: one report serves both.
class PulseReport final : public PulseSessionListener {
 public:
  explicit PulseReport(TrainReport& report) : report_(report) {}
  void session_started(const SessionStart& s) override { report_.session_started(s); }
  void trial_committed(const PulseTrialRecord& t, int total) override { report_.trial_committed(t, total); }

 private:
  TrainReport& report_;
};

void register_enrol(CLI::App* train) {
  struct Args {
    std::string curriculum, db;
    std::vector<std::string> trainees;
  };
  auto a = std::make_shared<Args>();
  auto* sub = train->add_subcommand("enrol", "Enrol trainees in a curriculum (the store is created when missing)");
  sub->add_option("--curriculum", a->curriculum, "Curriculum file (JSON)")->required();
  sub->add_option("--trainee", a->trainees, "A trainee's code (never their name); repeat for several")->required();
  sub->add_option("--db", a->db, "Trial store: an SQLite file or postgresql://user@host/db")->required();
  sub->callback([a] {
    const Curriculum c = load_curriculum(a->curriculum);
    for (const std::string& t : a->trainees) {
      enrol_trainee(a->db, c, t);
      std::cout << "palprig train: " << t << " enrolled in '" << c.name << "' (" << c.levels.size() << " levels) in "
                << a->db << "\n";
    }
  });
}

void register_next(CLI::App* train) {
  struct Args {
    TrainingRequest request;
    bool quiet = false;
    std::string level;
  };
  auto a = std::make_shared<Args>();
  auto* sub = train->add_subcommand(
      "next", "Run a trainee's next session at their present level (or continue the one they left unfinished)");
  sub->add_option("--curriculum", a->request.curriculum_file, "Curriculum file (JSON)")->required();
  sub->add_option("--trainee", a->request.trainee, "The trainee's code (enrolled with palprig train enrol)")
      ->required();
  sub->add_option("--db", a->request.store_location, "Trial store: an SQLite file or postgresql://user@host/db")
      ->required();
  sub->add_option("--participant", a->request.participant,
                  "sim:SEED: a simulated trainee answers, learning as the curriculum's pilot section says (a pilot "
                  "of the curriculum); default: the trainee themself, who palpates in the window (palprig gui)");
  sub->add_option("--level", a->level,
                  "Run this level instead of the present one (an expert's session for a benchmark)");
  sub->add_option("--sim-skill", a->request.simulated_skill,
                  "With sim:SEED: a simulated trainee of this fixed skill 0..1 instead of the pilot's (1: a simulated "
                  "expert)");
  sub->add_option("--journal", a->request.journal_file, "With a postgresql:// store: the bench's local journal");
  sub->add_option("--rig", a->request.rig_file, "Rig file (JSON); default: the simulated rig data/rigs/simulated.json");
  sub->add_option("--cal", a->request.calibration_file, "Calibration file (JSON); default: paper 002's models");
  sub->add_option("--telemetry", a->request.telemetry_file, "Record every rig tick of the session to FILE (new file)");
  sub->add_option("--speed", a->request.speed,
                  "Simulated trainee: 0 = as fast as simulated time allows (default), 1 = real time")
      ->check(CLI::Range(0.0, 1e6));
  sub->add_flag("--quiet", a->quiet, "Simulated trainee: no line per case");
  sub->callback([a] {
    TrainingRequest request = a->request;
    if (request.participant.empty()) {
      // A trainee palpates with the pen, which only the window reads: refused before anything.
      throw InputError("command line", "participant",
                       "sim:SEED at the terminal (a simulated trainee); the trainee themself palpates in the window: "
                       "palprig gui --curriculum " +
                           request.curriculum_file.string() + " --db " + request.store_location + " --participant " +
                           request.trainee);
    }
    if (!a->level.empty()) request.level = a->level;
    if (request.rig_file.empty()) request.rig_file = cli::data_dir() / "rigs" / "simulated.json";
    TrainReport report(a->quiet);
    PulseReport pulse_report(report);
    TrainingFrontEnd front;
    front.listener = &report;
    front.pulse_listener = &pulse_report;
    front.planned = [&](const TrainingPlanView& p) {
      std::string cases;
      for (const auto& c : p.cases) cases += (cases.empty() ? "" : ", ") + c;
      std::cout << "palprig train: " << p.trainee << ", '" << p.curriculum << "' level " << (p.level + 1) << " '"
                << p.level_name << "', session " << p.session_number << (p.resumed ? " (continued)" : "") << ", "
                << cli::counted(static_cast<long long>(p.cases.size()), "case", "cases") << ": " << cases << "\n"
                << std::flush;
    };
    install_stop_signals();
    const TrainingOutcome out = run_training_session(request, front, process_run_control());
    const Curriculum curriculum = load_curriculum(request.curriculum_file);
    if (const std::string telemetry = telemetry_summary(out.end); !telemetry.empty()) std::cout << telemetry << "\n";
    if (!out.scored) {
      if (!out.end.fault.empty())
        std::cerr << "palprig: rig fault: " << out.end.fault << "; ";
      else
        std::cerr << "palprig: ";
      std::cerr << "session stopped after " << out.end.committed_trials << " of " << out.end.total_trials
                << " cases (all kept); palprig train next continues it\n";
      cli::finish(cli::kExitFault);
    }
    std::cout << "session completed: " << scores_line(out.scores) << "\n";
    const CurriculumLevel& level = curriculum.levels.at(static_cast<std::size_t>(out.plan.level));
    if (out.benchmark.met) {
      std::cout << "  benchmark met";
    } else {
      std::string why;
      for (const auto& s : out.benchmark.shortfalls) why += (why.empty() ? "" : "; ") + s;
      std::cout << "  benchmark not met: " << why;
    }
    if (out.before.level != out.plan.level) {
      // A level other than the trainee's own (--level): their standing does not move.
      std::cout << "; a session at another level than theirs (" << level_text(curriculum, out.after.level) << ")\n";
    } else if (out.after.level > out.plan.level) {
      std::cout << "; level '" << level.name << "' passed after session " << out.after.sessions << "\n";
      if (out.after.finished)
        std::cout << "  every level of '" << curriculum.name << "' passed\n";
      else
        std::cout << "  next: " << level_text(curriculum, out.after.level) << "\n";
    } else {
      std::cout << " (" << out.after.consecutive_met << " of " << level.benchmark.consecutive_sessions
                << " sessions in a row at level '" << level.name << "')\n";
    }
  });
}

void register_status(CLI::App* train) {
  struct Args {
    std::string curriculum, db, trainee;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* sub = train->add_subcommand("status", "Where each trainee stands (or one trainee's sessions)");
  sub->add_option("--curriculum", a->curriculum, "Curriculum file (JSON)")->required();
  sub->add_option("--db", a->db, "Trial store: an SQLite file or postgresql://user@host/db")->required();
  sub->add_option("--trainee", a->trainee, "One trainee: every session with its scores");
  sub->add_flag("--json", a->json, "JSON instead of a table");
  sub->callback([a] {
    const Curriculum c = load_curriculum(a->curriculum);
    if (!a->trainee.empty()) {
      const TraineeStanding t = trainee_standing(a->db, c, a->trainee);
      if (a->json) {
        nlohmann::ordered_json j{{"trainee", t.trainee},
                                 {"curriculum", c.name},
                                 {"level", t.standing.level},
                                 {"finished", t.standing.finished},
                                 {"sessions", nlohmann::ordered_json::array()}};
        for (std::size_t i = 0; i < t.sessions.size(); ++i) {
          const auto& r = t.sessions[i];
          j["sessions"].push_back({{"session", i + 1},
                                   {"level", r.level_name},
                                   {"status", r.status},
                                   {"met_benchmark", r.met_benchmark ? nlohmann::ordered_json(*r.met_benchmark)
                                                                     : nlohmann::ordered_json(nullptr)},
                                   {"scores", r.scores}});
        }
        std::cout << j.dump(2) << "\n";
        return;
      }
      std::cout << "trainee " << t.trainee << ", '" << c.name << "': " << level_text(c, t.standing.level) << ", "
                << cli::counted(t.standing.sessions, "session", "sessions") << "\n";
      std::printf("  %-8s %-20s %-6s %-12s %-10s %-8s %-10s %s\n", "session", "level", "cases", "found", "marks/case",
                  "s/case", "normal", "benchmark");
      for (std::size_t i = 0; i < t.sessions.size(); ++i) {
        const auto& r = t.sessions[i];
        const SessionScores& s = t.scores[i];
        if (!r.completed()) {
          std::printf("  %-8zu %-20s %-6zu (unfinished: palprig train next continues it)\n", i + 1,
                      r.level_name.c_str(), r.cases.size());
          continue;
        }
        const std::string found = std::to_string(s.found()) + "/" + std::to_string(s.targets());
        const std::string normal =
            s.normal_cases() ? std::to_string(s.normal_called()) + "/" + std::to_string(s.normal_cases()) : "n/a";
        std::printf("  %-8zu %-20s %-6zu %-12s %-10s %-8s %-10s %s\n", i + 1, r.level_name.c_str(), s.cases.size(),
                    found.c_str(), fixed(s.false_marks_per_case(), 2).c_str(), fixed(s.time_per_case_s(), 1).c_str(),
                    normal.c_str(), r.met_benchmark.value_or(false) ? "met" : "not met");
      }
      return;
    }
    const std::vector<TraineeStanding> all = curriculum_standings(a->db, c);
    if (a->json) {
      nlohmann::ordered_json j = nlohmann::ordered_json::array();
      for (const auto& t : all) {
        j.push_back(
            {{"trainee", t.trainee},
             {"level", t.standing.level},
             {"level_name", t.standing.finished ? "" : c.levels[static_cast<std::size_t>(t.standing.level)].name},
             {"finished", t.standing.finished},
             {"sessions", t.standing.sessions},
             {"consecutive_met", t.standing.consecutive_met}});
      }
      std::cout << j.dump(2) << "\n";
      return;
    }
    std::cout << "curriculum '" << c.name
              << "': " << cli::counted(static_cast<long long>(all.size()), "trainee", "trainees") << "\n";
    std::printf("  %-12s %-34s %-9s %-9s %s\n", "trainee", "standing", "sessions", "at level", "in a row");
    for (const auto& t : all) {
      const std::string run =
          t.standing.finished
              ? "-"
              : std::to_string(t.standing.consecutive_met) + " of " +
                    std::to_string(c.levels[static_cast<std::size_t>(t.standing.level)].benchmark.consecutive_sessions);
      std::printf("  %-12s %-34s %-9d %-9d %s\n", t.trainee.c_str(), level_text(c, t.standing.level).c_str(),
                  t.standing.sessions, t.standing.sessions_at_level, run.c_str());
    }
  });
}

void register_benchmark(CLI::App* train) {
  struct Args {
    std::string curriculum, db, level, out;
    std::vector<std::string> experts;
    std::optional<double> percentile;
  };
  auto a = std::make_shared<Args>();
  auto* sub = train->add_subcommand(
      "benchmark",
      "A level's proficiency benchmark from experts' completed sessions at that level (mean or percentile)");
  sub->add_option("--curriculum", a->curriculum, "Curriculum file (JSON)")->required();
  sub->add_option("--db", a->db, "Trial store holding the experts' sessions")->required();
  sub->add_option("--level", a->level, "The level's name")->required();
  sub->add_option("--expert", a->experts, "An expert's code (enrolled; ran the level with train next --level)")
      ->required();
  sub->add_option("--percentile", a->percentile,
                  "P: found at the experts' P-th percentile, false marks and time at the (100-P)-th (P of every 100 "
                  "expert sessions fall short); default: the experts' mean")
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--out", a->out, "Write the curriculum with this level's benchmark replaced to FILE (a new file)");
  sub->callback([a] {
    const Curriculum c = load_curriculum(a->curriculum);
    const int level = level_index(c, a->level);
    const ExpertBenchmark b = expert_benchmark(a->db, c, level, a->experts, a->percentile);
    nlohmann::ordered_json j;
    if (b.benchmark.found_min) j["found_min"] = std::round(*b.benchmark.found_min * 1000) / 1000;
    if (b.benchmark.false_marks_per_case_max)
      j["false_marks_per_case_max"] = std::round(*b.benchmark.false_marks_per_case_max * 1000) / 1000;
    if (b.benchmark.time_per_case_max_s)
      j["time_per_case_max_s"] = std::round(*b.benchmark.time_per_case_max_s * 10) / 10;
    if (b.benchmark.normal_called_min)
      j["normal_called_min"] = std::round(*b.benchmark.normal_called_min * 1000) / 1000;
    j["consecutive_sessions"] = b.benchmark.consecutive_sessions;
    std::cout << "palprig train benchmark: level '" << a->level << "' from "
              << cli::counted(b.sessions, "expert session", "expert sessions") << " ("
              << (a->percentile ? "percentile " + fixed(*a->percentile, 0) : std::string("mean")) << ")\n"
              << "  \"benchmark\": " << j.dump() << "\n";
    if (!a->out.empty()) {
      nlohmann::json doc = c.snapshot;
      doc["levels"][static_cast<std::size_t>(level)]["benchmark"] = nlohmann::json::parse(j.dump());
      if (std::filesystem::exists(a->out)) {
        throw InputError("command line", "out", "a new file (" + a->out + " exists; it is never overwritten)");
      }
      CheckedOutputFile file(a->out);
      file.write(doc.dump(2) + "\n");
      file.commit();
      std::cout << "  written: " << a->out << "\n";
    }
  });
}

}  // namespace

void register_train_command(CLI::App& app) {
  auto* train = app.add_subcommand(
      "train", "Training programmes: trainees enrolled in a curriculum, their next session at their level, standing");
  train->require_subcommand(1);
  register_enrol(train);
  register_next(train);
  register_status(train);
  register_benchmark(train);
}
