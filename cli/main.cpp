// palprig: the command line. Subcommands register themselves from cli/*_command.cpp.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/data_files.hpp"
#include "cli/field_flags.hpp"
#include "cli/standard_output.hpp"
#include "core/error.hpp"
#include "core/input_error.hpp"

namespace {

int run_command(int argc, char** argv) {
  CLI::App app{"palprig: drive a pneumatic multi-finger palpation rig and run the studies done on it"};
  app.require_subcommand(1);
  // One version, project(palprig VERSION ...) in CMakeLists.txt, and the commit built from.
  app.set_version_flag("--version",
                       std::string("palprig " PALPRIG_VERSION " (commit ") + palprig::cli::git_commit() + ")");
  // The rig's commands (run, demo, experiment, calibrate, ...) come from rig_commands.cpp, or in an
  // analyst-only build from rig_commands_absent.cpp, which names them and refuses them.
  register_rig_commands(app);
  register_gui_command(app);  // gui_command.cpp, or gui_command_absent.cpp in a build without the window
  register_stats_command(app);
  register_export_command(app);
  register_scene_command(app);
  register_store_command(app);
  register_data_command(app);
  // Last: every registered option that takes a shipped file also takes its name (data_files.hpp).
  palprig::cli::resolve_data_names(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a subcommand finished with this exit code (see cli::finish)
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // One line, like every other refusal, instead of CLI11's two.
    std::cerr << "palprig: " << e.what() << " (see --help)\n";
    return palprig::cli::kExitBadInput;
  } catch (const palprig::InputError& e) {
    std::cerr << "palprig: " << palprig::cli::input_error_line(e) << "\n";
    return palprig::cli::kExitBadInput;
  } catch (const palprig::Error& e) {
    // The project's exception root (core/error.hpp): its class says the exit code (BadInput 2,
    // RigFault and any other Error 1).
    std::cerr << "palprig: " << e.what() << "\n";
    return e.exit_code();
  } catch (const std::exception& e) {
    // Not palprig's own (std::bad_alloc, a library's exception): a failure, not an answer.
    std::cerr << "palprig: " << e.what() << "\n";
    return palprig::cli::kExitFault;
  }
  return 0;
}

}  // namespace

// Standard output is checked to its last byte for every command (cli/standard_output.hpp).
int main(int argc, char** argv) {
  palprig::cli::check_standard_output();
  return palprig::cli::finish_standard_output(run_command(argc, argv));
}
