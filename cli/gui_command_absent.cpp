// A build without the window (-DPALPRIG_GUI=OFF, or the analyst-only build): `palprig gui`
// says so in one line instead of being an unknown subcommand.
#include <iostream>

#include "cli/commands.hpp"

void register_gui_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("gui", "(not in this build: configure with -DPALPRIG_GUI=ON, needs Qt6 Widgets)");
  sub->allow_extras();
  sub->callback([] {
    std::cerr << "palprig: gui: this build has no window (-DPALPRIG_GUI=OFF); rebuild with -DPALPRIG_GUI=ON\n";
    palprig::cli::finish(palprig::cli::kExitBadInput);
  });
}
