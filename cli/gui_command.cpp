// palprig gui: the Qt window (gui/). Parses the options and hands over to gui::run_gui.
#include <cmath>

#include "cli/commands.hpp"
#include "gui/gui_app.hpp"
#include "runtime/run_control.hpp"
#include "core/input_error.hpp"

using namespace palprig;

void register_gui_command(CLI::App& app) {
  struct Options {
    gui::GuiOptions gui;
    std::string telemetry;
    bool no_fifo = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      app.add_subcommand("gui", "The live rig console: pen on the scene view, finger pressures, VENT, traces");
  sub->add_option("--scene", o->gui.files.scene_path, "Scene file (JSON); default: the bundled phantom")
      ->check(CLI::ExistingFile);
  sub->add_option("--rig", o->gui.files.rig_path, "Rig file (JSON); default: the simulated rig");
  sub->add_option("--cal", o->gui.files.cal_path, "Calibration file (JSON); default: paper 002's models");
  sub->add_option(
         "--input", o->gui.files.input_spec,
         "Pen input: window (mouse or tablet on the scene view), trace:FILE, sweep, tablet[:DEVICE or FILE.evemu], "
         "igtl:HOST:PORT (tracked fingers, with --tracking)")
      ->default_val("window");
  sub->add_option("--tracking", o->gui.files.tracking_path,
                  "With --input igtl:HOST:PORT: the tracking file (which tool is which finger, tips, registration)")
      ->check(CLI::ExistingFile);
  sub->add_option("--rate-hz", o->gui.run.rate_hz, "Loop rate in Hz")
      ->default_val(1000.0)
      ->check(CLI::Range(1.0, 100000.0));
  sub->add_flag("--no-fifo", o->no_fifo, "Real time without SCHED_FIFO");
  sub->add_option("--telemetry", o->telemetry, "Write every tick to FILE (.csv, or .bin), as run does");
  sub->add_option("--screenshot", o->gui.screenshot_path,
                  "Save the whole window as PNG after --after-s seconds, then exit");
  sub->add_option("--after-s", o->gui.after_s, "Seconds of live operation before the screenshot")
      ->default_val(2.0)
      ->check(CLI::Range(0.1, 3600.0));
  sub->add_option("--protocol", o->gui.session.protocol,
                  "Open the experiment console on this protocol (with --participant and --db)");
  sub->add_option("--participant", o->gui.session.participant,
                  "Participant code, or sim:SEED for a pilot run with the simulated participant (it begins at once)");
  sub->add_option("--db", o->gui.session.store, "Trial database (SQLite; created when missing)");
  sub->add_option("--speed", o->gui.session.speed,
                  "Simulated participant on the simulated rig: 0 = as fast as possible (default), 1 = real time")
      ->check(CLI::Range(0.0, 1e6));
  sub->add_option("--session-telemetry", o->gui.session.telemetry,
                  "With --protocol: record every rig tick of the session to FILE (.bin or .csv), as experiment run "
                  "--telemetry does (--telemetry records the live loop)");
  sub->add_flag("--resume", o->gui.session.resume,
                "Continue this participant's unfinished session with this protocol at once");
  sub->add_option("--participant-display", o->gui.session.participant_display,
                  "Show the participant screen full screen on display N (1 = the first) from the start; "
                  "0 (default): inside the console")
      ->check(CLI::Range(0, 16));
  sub->add_option("--curriculum", o->gui.curriculum,
                  "Open the Training tab on this curriculum with --db (and the trainee --participant picked)");
  sub->add_flag("--json", o->gui.json, "At exit, print the loop's summary (ticks, overruns, wake-up latency) as JSON");
  sub->callback([o, sub]() {
    gui::GuiOptions g = o->gui;
    const auto& session = g.session;
    if (!session.protocol.empty() && (session.participant.empty() || session.store.empty())) {
      throw InputError("command line", session.participant.empty() ? "participant" : "store",
                       "a value with --protocol (the session needs a participant code and a trial database)");
    }
    if (!g.curriculum.empty() && (!session.protocol.empty() || session.store.empty())) {
      throw InputError("command line", session.store.empty() ? "db" : "curriculum",
                       session.store.empty() ? "a trial database with --curriculum (the trainees' store)"
                                             : "either --curriculum (the Training tab) or --protocol, not both");
    }
    if (session.participant_display > 0 && session.protocol.empty()) {
      throw InputError("command line", "participant-display",
                       "--protocol as well (the participant screen belongs to a session)");
    }
    g.files.data_dir = cli::data_dir();
    g.run.telemetry_path = o->telemetry;
    g.run.want_fifo = !o->no_fifo;
    install_stop_signals();
    g.run.control = &process_run_control();
    // Qt wants argc/argv for its own options; palprig's are already parsed.
    static int argc = 1;
    static char name[] = "palprig";
    static char* argv[] = {name, nullptr};
    (void)sub;
    const int code = gui::run_gui(argc, argv, g);
    if (code != 0) cli::finish(code);
  });
}
