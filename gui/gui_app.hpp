#pragma once
// run_gui: the `palprig gui` application from start to exit code. Loads and checks the files
// (a refusal is the CLI's one line, on stderr and in a dialog, exit 2, nothing opened), opens
// the rig, shows the main window, and with a screenshot path saves the whole window after
// after_s seconds of live operation and exits.
#include <atomic>
#include <string>

#include "gui/live_run.hpp"

namespace palprig::gui {

struct GuiOptions {
  LiveRunFiles files;
  LiveRunOptions run;
  std::string screenshot_path;  // empty: interactive
  double after_s = 2.0;         // with a screenshot: seconds of live operation first
  bool json = false;            // print the loop's summary as JSON at exit
};

// Exit codes as the CLI's: 0 done, 1 the rig faulted (vented), 2 a file was refused.
int run_gui(int argc, char** argv, const GuiOptions& options);

}  // namespace palprig::gui
