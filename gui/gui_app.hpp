#pragma once
// run_gui: the `palprig gui` application from start to exit code. Loads and checks the files
// (a refusal is the CLI's one line, on stderr and in a dialog, exit 2, nothing opened), opens
// the rig, shows the main window, and with a screenshot path saves the whole window after
// after_s seconds of live operation and exits.
#include <atomic>
#include <string>

#include "gui/live_run.hpp"

namespace palprig::gui {

// `palprig gui --protocol F --participant CODE --db F`: the console opens on that session. A
// simulated participant (sim:SEED, a pilot run) begins at once; a person's session begins on
// Begin (or at once with resume, continuing the unfinished session at the exact trial).
struct GuiSessionOptions {
  std::string protocol, participant, store;
  double speed = 0;
  bool resume = false;
  // 1-based display (QGuiApplication::screens() order) the participant screen fills at start,
  // while the console stays on its own; 0: the participant screen stays inside the console.
  int participant_display = 0;
  std::string telemetry;  // the session's rig ticks (--session-telemetry); empty: none
};

struct GuiOptions {
  LiveRunFiles files;
  LiveRunOptions run;
  std::string screenshot_path;  // empty: interactive
  double after_s = 2.0;         // with a screenshot: seconds of live operation first (a session:
                                // the screenshot is taken when it ends or after_s passed)
  GuiSessionOptions session;    // protocol empty: no session
  // A course: the Training tab opened on this curriculum and session.store (the trainee
  // session.participant picked, when given). Empty: none.
  std::string curriculum;
  bool json = false;  // print the loop's summary as JSON at exit
};

// Exit codes as the CLI's: 0 done, 1 the rig faulted (vented), 2 a file was refused. With a
// session: 1 also when the session faulted, 2 when it was refused.
int run_gui(int argc, char** argv, const GuiOptions& options);

}  // namespace palprig::gui
