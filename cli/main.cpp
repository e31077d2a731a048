// palprig: the command line. Subcommands register themselves from cli/*_command.cpp.
#include <csignal>
#include <cstdlib>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/field_flags.hpp"
#include "models/parse_error.hpp"


namespace palprig::cli {

std::atomic<int>& stop_signal() {
  static std::atomic<int> flag{0};
  return flag;
}

extern "C" void palprig_on_stop_signal(int sig) { stop_signal().store(sig); }

void install_stop_signals() {
  std::signal(SIGINT, palprig_on_stop_signal);
  std::signal(SIGTERM, palprig_on_stop_signal);
}

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("PALPRIG_DATA")) return env;
  return PALPRIG_SOURCE_DATA_DIR;
}

}  // namespace palprig::cli

int main(int argc, char** argv) {
  CLI::App app{"palprig: drive a pneumatic multi-finger palpation rig and run the studies done on it"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "palprig " PALPRIG_VERSION);
  register_run_command(app);
  register_demo_command(app);
  register_telemetry_command(app);
  register_stats_command(app);
  register_experiment_command(app);
  register_export_command(app);
  register_sim_rig_command(app);
  register_calibrate_command(app);
  register_scene_command(app);
  register_rt_check_command(app);
#ifdef PALPRIG_HAVE_GUI
  register_gui_command(app);  // the window needs Qt: cli/CMakeLists.txt leaves its file out otherwise
#endif
  register_store_command(app);
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
  } catch (const std::exception& e) {
    std::cerr << "palprig: " << e.what() << "\n";
    return palprig::cli::kExitFault;
  }
  return 0;
}
