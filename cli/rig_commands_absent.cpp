// The analyst-only build (-DPALPRIG_RIG=OFF) links no rig library: its palprig still knows the
// rig's command names and refuses each with one line, so a script run on an analyst's machine
// learns why instead of reading "unknown subcommand".
#include <iostream>

#include "cli/commands.hpp"

void register_rig_commands(CLI::App& app) {
  for (const char* name : {"run", "demo", "telemetry", "experiment", "sim-rig", "calibrate", "rt-check", "check",
                           "igtl-replay", "tracking", "load-cell", "train", "fe"}) {
    CLI::App* sub = app.add_subcommand(name, "(not in this analyst-only build: configure with -DPALPRIG_RIG=ON)");
    sub->allow_extras();
    sub->callback([name] {
      std::cerr << "palprig: " << name
                << ": this is an analyst-only build (-DPALPRIG_RIG=OFF) with stats, export, store and scene; "
                   "rebuild with -DPALPRIG_RIG=ON to drive a rig\n";
      palprig::cli::finish(palprig::cli::kExitBadInput);
    });
  }
}
